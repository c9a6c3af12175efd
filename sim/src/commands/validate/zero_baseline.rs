//! T-5.4-2 of `skyforge validate thesis`: the whole chain on the bundled zero-baseline
//! scenario. Synthesise [`SCENARIO`] into a temporary directory, run the bundled receiver
//! over its four recordings (ant1/ant2 x GPS L1 C/A / BDS B1I), and turn the two antennas'
//! RINEX observations into the table's rows ([`skyforge_validate::thesis::zero_baseline`]).
//! The validate crate cannot run this table itself: the synthesiser's writer and the
//! receiver's command live in this crate.

use super::super::receive::{ReceiveArgs, receive};
use super::super::synth::{DEFAULT_CHUNK_EPOCHS, synth};
use anyhow::Context;
use skyforge_receiver::input::InputParams;
use skyforge_validate::report::Row;
use skyforge_validate::thesis::zero_baseline::{SCENARIO, TABLE, rows_from_obs};
use std::path::Path;

/// The antennas of [`SCENARIO`] whose observations are differenced.
const ANTENNAS: [&str; 2] = ["ant1", "ant2"];
/// The recordings `synth` writes per antenna (`<antenna>.<tag>.sigmf-meta`).
const BAND_TAGS: [&str; 2] = ["gps-l1ca", "bds-b1i"];

/// What the receiver was given, appended to every row's note.
const RECEIVER_NOTE: &str = "; receiver: its default configuration (the a-priori choice, \
    not tuned to this table), assisted by the scenario's broadcast ephemerides (nav.rnx) and \
    rounded start position (receiver.toml) as written by synth";

/// Synthesise, receive and difference: the rows of T-5.4-2. The temporary directory (about
/// 2 GB of samples) is removed when done.
pub fn rows() -> anyhow::Result<Vec<Row>> {
    let tmp = tempfile::Builder::new()
        .prefix("skyforge-t-5.4-2-")
        .tempdir()
        .context("cannot create a temporary directory for the T-5.4-2 recordings")?;
    rows_in(tmp.path())
}

/// [`rows`] with its intermediate files under `work` (which must exist).
fn rows_in(work: &Path) -> anyhow::Result<Vec<Row>> {
    let synth_dir = work.join("synth");
    let receive_dir = work.join("receive");
    synth(
        SCENARIO,
        &synth_dir,
        None,
        false,
        DEFAULT_CHUNK_EPOCHS as usize,
    )
    .with_context(|| format!("{TABLE}: synthesising {SCENARIO}"))?;
    let files = ANTENNAS
        .iter()
        .flat_map(|a| {
            BAND_TAGS
                .iter()
                .map(move |tag| format!("{a}.{tag}.sigmf-meta"))
        })
        .map(|name| synth_dir.join(name))
        .collect();
    receive(&ReceiveArgs {
        files,
        params: InputParams::default(),
        assist: Some(synth_dir.join("nav.rnx")),
        config: Some(synth_dir.join("receiver.toml")),
        out: receive_dir.clone(),
        force: false,
    })
    .with_context(|| format!("{TABLE}: the receiver on {SCENARIO}"))?;
    let [a, b] = ANTENNAS.map(|a| receive_dir.join(format!("{a}.obs.rnx")));
    let mut rows = rows_from_obs(&a, &b).with_context(|| format!("{TABLE}: double differences"))?;
    for row in &mut rows {
        row.note.push_str(RECEIVER_NOTE);
    }
    Ok(rows)
}
