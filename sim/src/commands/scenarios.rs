//! `skyforge scenarios list|show`.

use crate::bad_input::BadInput;

/// Print bundled scenario names and summaries.
pub fn list() -> anyhow::Result<()> {
    for b in skyforge_scenarios::bundled() {
        println!("{:<18} {}", b.name, b.summary);
    }
    Ok(())
}

/// Print one bundled scenario's TOML.
pub fn show(name: &str) -> anyhow::Result<()> {
    let all = skyforge_scenarios::bundled();
    match all.iter().find(|b| b.name == name) {
        Some(b) => {
            print!("{}", b.text);
            Ok(())
        }
        None => {
            let names: Vec<&str> = all.iter().map(|b| b.name).collect();
            Err(BadInput(format!(
                "no bundled scenario {name:?}; bundled: {}",
                names.join(", ")
            ))
            .into())
        }
    }
}
