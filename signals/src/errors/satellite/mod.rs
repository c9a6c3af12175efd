//! Satellite-side errors: the signal leaves a satellite whose true orbit and clock differ
//! from those its navigation message broadcasts (`[errors.satellite]`, opt-in).
//!
//! The error of each satellite is a set of smoothed first-order Gauss-Markov paths
//! ([`gauss_markov`]): the orbit error in the satellite's radial, along-track and
//! cross-track axes and the clock error, each from its own random stream keyed by the
//! scenario seed and the satellite (never by antenna or platform), so every antenna of a
//! run sees the same satellite error. The models ([`presets`]): the book's SA-era
//! processes, today's broadcast-ephemeris errors per system, or processes of the user's.
//! The geometry truth applies them (`truth::TrueSatellite`); the navigation messages keep
//! broadcasting the ephemerides as they were.

pub(crate) mod gauss_markov;
pub(crate) mod precise;
pub(crate) mod presets;

pub use gauss_markov::SmoothGaussMarkov;
pub use precise::{PreciseOrbit, precise_orbits};
pub use presets::{BOOK_SA, W_R, modern, sisre_m, w_ac_squared};

use super::seed::{Stream, stream_rng};
use serde::Deserialize;
use skyforge_orbits::Vec3;
use skyforge_orbits::check::{Allowed, Invalid, check_table};
use skyforge_orbits::ephemeris::{SatId, System};
use std::collections::BTreeMap;

/// Time the error paths cover before the start and after the end of a run (s): more than
/// any light time, geometry stencil or receiver look-back reaches.
const SPAN_MARGIN_S: f64 = 600.0;
/// At most this many nodes per path (a year at 1 s spacing is 3.2e7).
const MAX_NODES: f64 = 1e7;

/// `[errors.satellite]`: which satellite-side error model the signals follow.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SatelliteErrorConfig {
    pub model: SatelliteModel,
    /// `[errors.satellite.processes]`: the processes of `model = "gauss-markov"`.
    #[serde(default)]
    pub processes: Option<SatelliteProcesses>,
    /// The SP3 file of `model = "precise"` (relative paths start at the scenario's
    /// folder).
    #[serde(default)]
    pub sp3: Option<std::path::PathBuf>,
}

/// The satellite-side error models.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SatelliteModel {
    /// The book's SA-era processes (Table 2-19): [`BOOK_SA`] for every system.
    BookSa,
    /// Today's broadcast orbit and clock errors, per system ([`modern`]).
    Modern,
    /// The user's processes (`[errors.satellite.processes]`), the same for every system.
    GaussMarkov,
    /// Real precise orbits and clocks of the scenario's day (`sp3`) against its broadcast
    /// ephemerides ([`precise`]).
    Precise,
}

impl From<SatelliteModel> for SatelliteErrorConfig {
    /// A model without processes of its own (`book-sa`, `modern`).
    fn from(model: SatelliteModel) -> Self {
        Self {
            model,
            processes: None,
            sp3: None,
        }
    }
}

/// The error processes of one satellite: standard deviations and correlation times.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SatelliteProcesses {
    /// Radial orbit error, 1 sigma (m).
    pub radial_m: f64,
    /// Along-track orbit error, 1 sigma (m).
    pub along_m: f64,
    /// Cross-track orbit error, 1 sigma (m).
    pub cross_m: f64,
    /// Correlation time of the orbit error (s).
    pub orbit_tau_s: f64,
    /// Clock error times c, 1 sigma (m).
    pub clock_m: f64,
    /// Correlation time of the clock error (s).
    pub clock_tau_s: f64,
    /// Spacing of the spline nodes (s): sets how smooth the paths are over lags shorter
    /// than it (see [`gauss_markov`]).
    pub node_spacing_s: f64,
}

/// Bounds of [`SatelliteProcesses`]: errors up to 1 km (SA's epsilon reached about 100 m),
/// correlation times up to a year, nodes from 1 s (the geometry stencil's step) to a day.
const SIGMA_M: Allowed = Allowed::closed(0.0, 1000.0, "m");
const TAU_S: Allowed = Allowed::above(0.0, 3.2e7, "s");
const NODE_SPACING_S: Allowed = Allowed::closed(1.0, 86_400.0, "s");

impl SatelliteProcesses {
    /// Every field inside its bounds.
    pub fn check(&self) -> Result<(), Invalid> {
        check_table(&[
            ("radial_m", self.radial_m, SIGMA_M),
            ("along_m", self.along_m, SIGMA_M),
            ("cross_m", self.cross_m, SIGMA_M),
            ("orbit_tau_s", self.orbit_tau_s, TAU_S),
            ("clock_m", self.clock_m, SIGMA_M),
            ("clock_tau_s", self.clock_tau_s, TAU_S),
            ("node_spacing_s", self.node_spacing_s, NODE_SPACING_S),
        ])
    }
}

impl SatelliteErrorConfig {
    /// The `gauss-markov` model with `processes`.
    pub fn gauss_markov(processes: SatelliteProcesses) -> Self {
        Self {
            model: SatelliteModel::GaussMarkov,
            processes: Some(processes),
            sp3: None,
        }
    }

    /// The processes of `system`'s satellites (none for precise orbits, and for a
    /// `gauss-markov` model without processes, which `check` refuses).
    pub fn processes(&self, system: System) -> Option<SatelliteProcesses> {
        match self.model {
            SatelliteModel::BookSa => Some(BOOK_SA),
            SatelliteModel::Modern => Some(modern(system)),
            SatelliteModel::GaussMarkov => self.processes,
            SatelliteModel::Precise => None,
        }
    }

    /// Processes given exactly for `gauss-markov`, inside their bounds, and a run of
    /// `duration_s` within [`MAX_NODES`] nodes per path; an SP3 file exactly for `precise`.
    pub fn check(&self, duration_s: f64) -> Result<(), Invalid> {
        match (self.model, &self.sp3) {
            (SatelliteModel::Precise, None) => {
                return Err(Invalid::new(
                    "sp3",
                    "(missing)",
                    "model = \"precise\" needs the SP3 file of the scenario's day",
                ));
            }
            (SatelliteModel::Precise, Some(_)) | (_, None) => {}
            (_, Some(path)) => {
                return Err(Invalid::new(
                    "sp3",
                    format!("{:?}", path.display().to_string()),
                    "only model = \"precise\" reads an SP3 file",
                ));
            }
        }
        let p = match (self.model, &self.processes) {
            (SatelliteModel::GaussMarkov, Some(p)) => p,
            (SatelliteModel::GaussMarkov, None) => {
                return Err(Invalid::new(
                    "processes",
                    "(missing)",
                    "model = \"gauss-markov\" needs an [errors.satellite.processes] table",
                ));
            }
            (_, Some(_)) => {
                return Err(Invalid::new(
                    "processes",
                    "(a table)",
                    "only model = \"gauss-markov\" takes processes; the other models bring their own",
                ));
            }
            (_, None) => return Ok(()),
        };
        p.check().map_err(|e| e.within("processes"))?;
        let nodes = (duration_s + 2.0 * SPAN_MARGIN_S) / p.node_spacing_s;
        if nodes > MAX_NODES {
            return Err(Invalid::new(
                "processes.node_spacing_s",
                p.node_spacing_s,
                format!(
                    "gives {nodes:.0} nodes over the run; at most {MAX_NODES:e} \
                     (a larger spacing, or a shorter run)"
                ),
            ));
        }
        Ok(())
    }
}

/// What one satellite's signal follows instead of its broadcast ephemeris.
#[derive(Debug, Clone, PartialEq)]
pub enum SatelliteTrack {
    /// Drawn error paths added to the broadcast orbit and clock.
    Drawn(DrawnTrack),
    /// A precise orbit and clock.
    Precise(PreciseOrbit),
}

/// One satellite's drawn error paths.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawnTrack {
    /// Radial, along-track, cross-track (m).
    orbit: [SmoothGaussMarkov; 3],
    /// Clock error times c (m).
    clock: SmoothGaussMarkov,
}

impl DrawnTrack {
    /// The orbit error at `t_s` (s from the start, transmit time) in the radial,
    /// along-track and cross-track axes (m).
    pub fn orbit_rac_m(&self, t_s: f64) -> Vec3 {
        Vec3::from_fn(|i, _| self.orbit[i].value_and_rate(t_s).0)
    }

    /// The clock error at `t_s` times c (m; positive: the satellite clock is ahead of the
    /// broadcast one, so the pseudorange is shorter) and its rate (m/s).
    pub fn clock_m_and_rate(&self, t_s: f64) -> (f64, f64) {
        self.clock.value_and_rate(t_s)
    }
}

/// The error tracks of every satellite of a run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SatelliteErrors {
    tracks: BTreeMap<SatId, SatelliteTrack>,
}

/// The key of a satellite's random streams: unique per system and PRN.
fn stream_index(sat: SatId) -> u32 {
    let system = match sat.system {
        System::Gps => 0,
        System::Beidou => 1,
        System::Galileo => 2,
    };
    (system << 8) | u32::from(sat.prn)
}

impl SatelliteErrors {
    /// Draw the tracks of `satellites` over a run of `duration_s` with the scenario seed
    /// (none for a model without processes: precise orbits come from [`Self::precise`]).
    /// The paths start at a fixed time before the run, so a longer run extends a shorter
    /// one's paths with the same values.
    pub fn draw(
        config: &SatelliteErrorConfig,
        seed: u64,
        satellites: &[SatId],
        duration_s: f64,
    ) -> Self {
        let tracks = satellites
            .iter()
            .filter_map(|&sat| {
                let p = config.processes(sat.system)?;
                let dt = p.node_spacing_s;
                let t0 = -SPAN_MARGIN_S - 2.0 * dt;
                let n = ((duration_s + 2.0 * SPAN_MARGIN_S) / dt).ceil() as usize + 5;
                let key = stream_index(sat);
                let path = |sigma: f64, tau: f64, stream: Stream| {
                    if sigma == 0.0 {
                        SmoothGaussMarkov::zero(t0, dt)
                    } else {
                        SmoothGaussMarkov::draw(
                            sigma,
                            tau,
                            t0,
                            dt,
                            n,
                            &mut stream_rng(seed, stream, key),
                        )
                    }
                };
                let track = SatelliteTrack::Drawn(DrawnTrack {
                    orbit: [
                        path(p.radial_m, p.orbit_tau_s, Stream::SatelliteRadial),
                        path(p.along_m, p.orbit_tau_s, Stream::SatelliteAlong),
                        path(p.cross_m, p.orbit_tau_s, Stream::SatelliteCross),
                    ],
                    clock: path(p.clock_m, p.clock_tau_s, Stream::SatelliteClock),
                });
                Some((sat, track))
            })
            .collect();
        Self { tracks }
    }

    /// Satellites following precise orbits and clocks (see [`precise_orbits`]).
    pub fn precise(orbits: BTreeMap<SatId, PreciseOrbit>) -> Self {
        Self {
            tracks: orbits
                .into_iter()
                .map(|(sat, o)| (sat, SatelliteTrack::Precise(o)))
                .collect(),
        }
    }

    /// The track of `sat` (none when it was not drawn).
    pub fn track(&self, sat: SatId) -> Option<&SatelliteTrack> {
        self.tracks.get(&sat)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn drawn(errors: &SatelliteErrors, sat: SatId) -> &DrawnTrack {
        match errors.track(sat) {
            Some(SatelliteTrack::Drawn(d)) => d,
            other => panic!("{sat}: {other:?}"),
        }
    }

    #[test]
    fn tracks_are_keyed_by_satellite_and_a_longer_run_extends_a_shorter_one() {
        let sats = [SatId::gps(3), SatId::gps(7), SatId::beidou(3)];
        let short = SatelliteErrors::draw(&SatelliteModel::BookSa.into(), 5, &sats, 600.0);
        let long = SatelliteErrors::draw(&SatelliteModel::BookSa.into(), 5, &sats[..2], 7200.0);
        for t in [-10.0, 0.0, 123.4, 599.0] {
            assert_eq!(
                drawn(&short, SatId::gps(7)).orbit_rac_m(t),
                drawn(&long, SatId::gps(7)).orbit_rac_m(t)
            );
        }
        let (a, b, c) = (
            drawn(&short, SatId::gps(3)).clock_m_and_rate(0.0),
            drawn(&short, SatId::gps(7)).clock_m_and_rate(0.0),
            drawn(&short, SatId::beidou(3)).clock_m_and_rate(0.0),
        );
        assert!(a != b && a != c && b != c);
        assert!(long.track(SatId::beidou(3)).is_none());
        let other_seed = SatelliteErrors::draw(&SatelliteModel::BookSa.into(), 6, &sats, 600.0);
        assert_ne!(other_seed.track(SatId::gps(3)), short.track(SatId::gps(3)));
    }

    #[test]
    fn zero_sigmas_give_zero_errors_and_bad_processes_are_refused() {
        let p = SatelliteProcesses {
            radial_m: 0.0,
            along_m: 0.0,
            cross_m: 0.0,
            orbit_tau_s: 100.0,
            clock_m: 0.0,
            clock_tau_s: 100.0,
            node_spacing_s: 10.0,
        };
        let config = SatelliteErrorConfig::gauss_markov(p);
        let e = SatelliteErrors::draw(&config, 1, &[SatId::gps(1)], 100.0);
        let track = drawn(&e, SatId::gps(1));
        assert_eq!(track.orbit_rac_m(50.0), Vec3::zeros());
        assert_eq!(track.clock_m_and_rate(50.0), (0.0, 0.0));
        assert!(config.check(100.0).is_ok());
        let bad = SatelliteErrorConfig::gauss_markov(SatelliteProcesses {
            clock_tau_s: 0.0,
            ..p
        });
        assert_eq!(bad.check(100.0).unwrap_err().field, "processes.clock_tau_s");
        let dense = SatelliteErrorConfig::gauss_markov(SatelliteProcesses {
            node_spacing_s: 1.0,
            ..p
        });
        let err = dense.check(1e8).unwrap_err();
        assert_eq!(err.field, "processes.node_spacing_s");
        let missing = SatelliteErrorConfig::from(SatelliteModel::GaussMarkov);
        assert_eq!(missing.check(100.0).unwrap_err().field, "processes");
        let extra = SatelliteErrorConfig {
            model: SatelliteModel::Modern,
            processes: Some(p),
            sp3: None,
        };
        assert_eq!(extra.check(100.0).unwrap_err().field, "processes");
        let no_file = SatelliteErrorConfig::from(SatelliteModel::Precise);
        assert_eq!(no_file.check(100.0).unwrap_err().field, "sp3");
        let stray_file = SatelliteErrorConfig {
            sp3: Some("day.sp3".into()),
            ..SatelliteModel::BookSa.into()
        };
        assert_eq!(stray_file.check(100.0).unwrap_err().field, "sp3");
    }

    #[test]
    fn the_model_is_chosen_in_toml() {
        let c: SatelliteErrorConfig = toml::from_str("model = \"book-sa\"").unwrap();
        assert_eq!(c, SatelliteModel::BookSa.into());
        let c: SatelliteErrorConfig = toml::from_str(
            "model = \"gauss-markov\"\n[processes]\nradial_m = 1\nalong_m = 2\ncross_m = 3\n\
             orbit_tau_s = 3600\nclock_m = 4\nclock_tau_s = 600\nnode_spacing_s = 30",
        )
        .unwrap();
        assert_eq!(c.processes(System::Beidou).unwrap().cross_m, 3.0);
        assert!(toml::from_str::<SatelliteErrorConfig>("model = \"sa\"").is_err());
        assert!(
            toml::from_str::<SatelliteErrorConfig>("model = \"book-sa\"\nclock_m = 1").is_err()
        );
    }
}
