//! `skyforge jamming`: one antenna's observation file through the C/N0 jamming monitor
//! (`navigation::interference`), written to `DIR/interference.csv`
//! (`formats::interference`).

use crate::bad_input::BadInput;
use crate::cli::JammingArgs;
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use skyforge_formats::interference::{INTERFERENCE_CSV, write_interference_csv};
use skyforge_navigation::interference::{Cn0Monitor, Cn0MonitorConfig, JammingEpoch};

/// Run `skyforge jamming`.
pub fn jamming(args: &JammingArgs) -> anyhow::Result<()> {
    let config = Cn0MonitorConfig {
        false_alarm: args.false_alarm,
        ..Cn0MonitorConfig::default()
    };
    let mut monitor = Cn0Monitor::new(config)
        .map_err(|_| BadInput(format!("--false-alarm {}: in (0, 0.5)", args.false_alarm)))?;
    let file = super::read_observations(&args.file)?;
    let epochs: Vec<JammingEpoch> = file.epochs.iter().map(|e| monitor.epoch(e)).collect();
    let staged = StagedDir::create(&args.out, args.force)?;
    let path = staged.file(INTERFERENCE_CSV);
    write_interference_csv(&path, &epochs)
        .with_context(|| format!("writing {}", path.display()))?;
    let dir = staged.commit()?;
    let alarms = epochs.iter().filter(|e| e.alarm).count();
    let first = epochs.iter().find(|e| e.alarm).map(|e| e.t.to_string());
    println!(
        "epochs     {} ({alarms} with the alarm raised; first {})",
        epochs.len(),
        first.as_deref().unwrap_or("none")
    );
    println!("wrote      {}", dir.join(INTERFERENCE_CSV).display());
    Ok(())
}
