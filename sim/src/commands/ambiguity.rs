//! `skyforge ambiguity FILE`: LAMBDA on a float solution read from a file.

use crate::bad_input::BadInput;
use skyforge_navigation::ambiguity::{IntegerSolution, lambda, problem_file};
use std::path::Path;

/// Read `file`, resolve its ambiguities and print `candidates` integer vectors.
pub fn ambiguity(file: &Path, candidates: usize, json: bool) -> anyhow::Result<()> {
    let problem = problem_file::read_problem(file).map_err(|e| BadInput(e.to_string()))?;
    let sol = lambda(&problem.a_hat, &problem.q, candidates)
        .map_err(|e| BadInput(format!("{}: {e}", file.display())))?;
    if json {
        println!("{}", serde_json::to_string_pretty(&to_json(&sol))?);
    } else {
        print_text(file, &sol);
    }
    Ok(())
}

fn z_rows(sol: &IntegerSolution) -> Vec<Vec<i64>> {
    let z = &sol.z;
    (0..z.nrows())
        .map(|i| (0..z.ncols()).map(|j| z[(i, j)] as i64).collect())
        .collect()
}

fn to_json(sol: &IntegerSolution) -> serde_json::Value {
    let candidates: Vec<serde_json::Value> = sol
        .candidates
        .iter()
        .map(|c| serde_json::json!({"integers": c.integers, "squared_norm": c.squared_norm}))
        .collect();
    serde_json::json!({
        "n": sol.z.nrows(),
        "candidates": candidates,
        "ratio": sol.ratio().filter(|r| r.is_finite()),
        "success_rate": sol.success_rate,
        "z": z_rows(sol),
    })
}

fn print_text(file: &Path, sol: &IntegerSolution) {
    println!("{}: {} ambiguities", file.display(), sol.z.nrows());
    println!(
        "bootstrapped success rate (decorrelated): {:.6}",
        sol.success_rate
    );
    match sol.ratio() {
        Some(r) => println!("ratio (second-best / best squared norm): {r:.4}"),
        None => println!("ratio: n/a (one candidate)"),
    }
    println!("candidates (best first):");
    for (i, c) in sol.candidates.iter().enumerate() {
        let ints: Vec<String> = c.integers.iter().map(i64::to_string).collect();
        println!(
            "  {:>3}  squared norm {:<14.6}  [{}]",
            i + 1,
            c.squared_norm,
            ints.join(", ")
        );
    }
    println!("decorrelating Z (z = Z^T a):");
    for row in z_rows(sol) {
        let cells: Vec<String> = row.iter().map(|v| format!("{v:>4}")).collect();
        println!("  [{} ]", cells.join(""));
    }
}
