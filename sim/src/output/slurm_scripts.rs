//! The Slurm scripts of `skyforge study slurm`: a job array with one task per shard
//! (`--shard ${SLURM_ARRAY_TASK_ID}/n`, requeueable: a requeued task resumes from its
//! journal), a merge job, and `submit.sh`, which submits the array and the merge with
//! `--dependency=afterok` on it.

use super::whole_file;
use std::path::Path;

/// How the job scripts begin (their job names all start `skyforge-`).
const JOB_START: &str = "#!/bin/bash\n#SBATCH --job-name=skyforge-";
/// How `submit.sh` begins.
const SUBMIT_START: &str =
    "#!/bin/bash\n# Submit the study's job array and its merge job (after every task succeeded).\n";

/// Whether the file at `path` is a script `study slurm` wrote (it begins as one).
pub fn written_by_skyforge(path: &Path) -> bool {
    [JOB_START, SUBMIT_START]
        .iter()
        .any(|start| whole_file::starts_with(path, start.as_bytes()))
}

/// What the scripts run and where.
#[derive(Debug, Clone)]
pub struct SlurmJob<'a> {
    /// The `skyforge` binary as the cluster's nodes see it.
    pub skyforge: &'a Path,
    pub study: &'a Path,
    /// The study's output directory (shared by every node).
    pub out: &'a Path,
    pub shards: u64,
    /// The study's name (in job names, reduced to letters, digits, `-` and `_`).
    pub name: &'a str,
    /// Extra `#SBATCH` options, e.g. `--partition=short`.
    pub options: &'a [String],
}

/// `text` (a path or an option, named `what`) refused when it holds a control character:
/// a newline in a `#SBATCH` or comment line of a script ends it, and what follows runs as
/// a command when the job runs.
pub fn refuse_control_characters(what: &str, text: &str) -> Result<(), String> {
    match text.chars().find(|c| c.is_control()) {
        Some(c) => Err(format!(
            "{what} {text:?} holds the control character U+{:04X}, which cannot go into a Slurm script: choose one without",
            u32::from(c)
        )),
        None => Ok(()),
    }
}

/// `text` (a path, named `what`) refused when it holds a backslash: Slurm reads a
/// backslash in a log path as "no patterns", so `shard-%a.log` would not name the task.
pub fn refuse_backslash(what: &str, text: &str) -> Result<(), String> {
    if text.contains('\\') {
        return Err(format!(
            "{what} {text:?} holds a backslash, which Slurm reads in a log path as \"no patterns\": choose a path without"
        ));
    }
    Ok(())
}

/// `text` as one value on an `#SBATCH` line: in double quotes, `\` and `"` escaped
/// (sbatch's own parser of the line, checked with slurm-wlm 22.05: a space, `'`, `#`,
/// `$(...)` and backquotes inside the quotes stay as they are).
fn sbatch_value(text: &str) -> String {
    format!("\"{}\"", text.replace('\\', "\\\\").replace('"', "\\\""))
}

/// An `--sbatch` option as an `#SBATCH` line's words: `--name=value` with the value
/// quoted as one ([`sbatch_value`]), so that `--comment=cn0 sweep` stays one comment; an
/// option without `=` (`--exclusive`, `-p short`) as given.
fn sbatch_option(option: &str) -> String {
    match option.split_once('=') {
        Some((name, value)) => format!("{name}={}", sbatch_value(value)),
        None => option.to_string(),
    }
}

/// `path` quoted for a POSIX shell.
fn quoted(path: &Path) -> String {
    format!("'{}'", path.display().to_string().replace('\'', r"'\''"))
}

impl SlurmJob<'_> {
    fn job_name(&self) -> String {
        let name: String = self
            .name
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        format!("skyforge-{name}")
    }

    /// The `#SBATCH` lines. The log path is a Slurm filename pattern (`log` holds `%a`),
    /// so a `%` of the output directory is written `%%`.
    fn header(&self, name: &str, log: &str) -> String {
        let dir = self
            .out
            .join("slurm")
            .display()
            .to_string()
            .replace('%', "%%");
        debug_assert!(name.starts_with("skyforge-"));
        let mut s = format!(
            "#!/bin/bash\n#SBATCH --job-name={name}\n#SBATCH --output={}\n",
            sbatch_value(&format!("{dir}/{log}"))
        );
        for o in self.options {
            s.push_str(&format!("#SBATCH {}\n", sbatch_option(o)));
        }
        s
    }

    /// The job array: task i makes shard i of n.
    pub fn array(&self) -> String {
        format!(
            "{}#SBATCH --array=1-{n}\n#SBATCH --requeue\n# Task i makes shard i of {n}; a requeued or resubmitted task resumes from its\n# journal ({out}/shard-i-of-{n}.runs.jsonl).\nset -euo pipefail\nexec {exe} study run {study} --out {out_q} --shard \"${{SLURM_ARRAY_TASK_ID}}/{n}\"\n",
            self.header(&self.job_name(), "shard-%a.log"),
            n = self.shards,
            out = self.out.display(),
            exe = quoted(self.skyforge),
            study = quoted(self.study),
            out_q = quoted(self.out),
        )
    }

    /// The merge job.
    pub fn merge(&self) -> String {
        format!(
            "{}set -euo pipefail\nexec {exe} study merge {out}\n",
            self.header(&format!("{}-merge", self.job_name()), "merge.log"),
            exe = quoted(self.skyforge),
            out = quoted(self.out),
        )
    }

    /// `submit.sh`: the array, then the merge once every task succeeded; prints both job
    /// ids.
    pub fn submit(&self) -> String {
        let dir = quoted(&self.out.join("slurm"));
        format!(
            "{SUBMIT_START}set -euo pipefail\narray=$(sbatch --parsable {dir}/array.sbatch)\nmerge=$(sbatch --parsable --dependency=afterok:\"${{array%%;*}}\" {dir}/merge.sbatch)\necho \"array job ${{array%%;*}}, merge job ${{merge%%;*}}\"\n"
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_refused() {
        let e = refuse_control_characters("--out", "W/x\ntouch W/PWNED").unwrap_err();
        assert!(
            e.contains("--out \"W/x\\ntouch W/PWNED\" holds the control character U+000A"),
            "{e}"
        );
        assert!(refuse_control_characters("--out", "a\u{1b}[2J").is_err());
        assert!(refuse_control_characters("--out", "/data/sky forge/it's $(x) `y` #z").is_ok());
        assert!(refuse_backslash("--out", "/data/a\\b").is_err());
        assert!(refuse_backslash("--out", "/data/sky forge/it's $(x) `y` #z").is_ok());
    }

    #[test]
    fn scripts_quote_paths_and_name_the_shards() {
        let options = [
            "--partition=short".to_string(),
            "--comment=say \"hi\" # now".to_string(),
            "-p short".to_string(),
        ];
        let job = SlurmJob {
            skyforge: Path::new("/opt/sky forge/skyforge"),
            study: Path::new("/data/it's.toml"),
            out: Path::new("/data/out 50%"),
            shards: 4,
            name: "cn0 sweep!",
            options: &options,
        };
        let a = job.array();
        assert!(a.contains("#SBATCH --array=1-4\n"), "{a}");
        assert!(
            a.contains("#SBATCH --job-name=skyforge-cn0_sweep_\n"),
            "{a}"
        );
        assert!(a.contains("#SBATCH --partition=\"short\"\n"), "{a}");
        assert!(
            a.contains("#SBATCH --comment=\"say \\\"hi\\\" # now\"\n"),
            "{a}"
        );
        assert!(a.contains("#SBATCH -p short\n"), "{a}");
        assert!(
            a.contains("#SBATCH --output=\"/data/out 50%%/slurm/shard-%a.log\"\n"),
            "{a}"
        );
        assert!(a.contains("exec '/opt/sky forge/skyforge' study run '/data/it'\\''s.toml' --out '/data/out 50%' --shard \"${SLURM_ARRAY_TASK_ID}/4\""), "{a}");
        assert!(job.merge().contains("study merge '/data/out 50%'"));
        assert!(job.submit().contains("--dependency=afterok:"));
    }
}
