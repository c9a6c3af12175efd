//! One antenna x satellite link as the renderer sees it: the link's state at the geometry
//! epochs ([`LinkEnd`]), its interpolation across one geometry interval ([`Segment`]),
//! and the signal truth recorded from it ([`LinkTruth`]).
//!
//! Delays of the direct path at true receive time `t` (all in seconds of signal travel):
//!
//! - code:    `D_code(t) = tau(t) + (I + T + A) / c - dt_sv`
//! - carrier: `D_carr(t) = tau(t) + (-I + T + A) / c - dt_sv`
//!
//! with `tau` the geometric light time, `I` the ionospheric group delay (dispersive: it
//! advances the carrier), `T` the tropospheric delay, `A` the phase-centre offset and
//! variation delay (both non-dispersive), `dt_sv` the satellite clock offset. The receiver
//! clock and the fault events are added by the renderer; reflected paths add their own
//! delay, amplitude and phase on top of the direct path.

use crate::errors::multipath::Path;
use crate::truth::geometry::LinkGeometry;
use crate::truth::interp::QuinticHermite;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;

/// One end (a geometry epoch) of a link's interval.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkEnd {
    pub range_m: f64,
    pub range_rate_mps: f64,
    pub range_accel_mps2: f64,
    pub sat_clock_s: f64,
    pub sat_clock_drift: f64,
    /// Ionospheric group delay at the signal's carrier (m): delays the code, advances the
    /// carrier by the same amount.
    pub iono_m: f64,
    /// Tropospheric delay (m), code and carrier alike.
    pub tropo_m: f64,
    /// Phase-centre offset and variation delay (m), code and carrier alike.
    pub antenna_m: f64,
    /// The phase-centre delay (m) of every signal ([`Signal::ALL`]) where the antenna has
    /// a phase centre per signal, for a link's observed-only signals; empty when every
    /// signal has `antenna_m`.
    pub antenna_by_signal_m: Vec<(Signal, f64)>,
    /// C/N0 of the direct path (dB-Hz).
    pub cn0_dbhz: f64,
    /// Reflected paths in a fixed order per link (a path absent at this epoch has
    /// amplitude 0, so the ends of an interval pair up).
    pub reflections: Vec<Path>,
}

impl LinkEnd {
    /// The link end with the satellite clock of a signal whose broadcast group delay is
    /// `group_delay_s`: the signal's clock is the broadcast polynomial minus it
    /// ([`skyforge_gnss::signal::Signal::broadcast_group_delay_s`]), for code and carrier.
    pub fn with_group_delay(self, group_delay_s: f64) -> Self {
        Self {
            sat_clock_s: self.sat_clock_s - group_delay_s,
            ..self
        }
    }

    /// The link end of a geometry-truth link at `cn0_dbhz` with no error terms yet, `None`
    /// when not visible.
    pub fn from_geometry(g: &LinkGeometry, cn0_dbhz: f64) -> Option<Self> {
        g.visible.then_some(Self {
            range_m: g.range_m,
            range_rate_mps: g.range_rate_mps,
            range_accel_mps2: g.range_accel_mps2,
            sat_clock_s: g.sat_clock_s,
            sat_clock_drift: g.sat_clock_drift,
            iono_m: 0.0,
            tropo_m: 0.0,
            antenna_m: 0.0,
            antenna_by_signal_m: Vec::new(),
            cn0_dbhz,
            reflections: Vec::new(),
        })
    }
}

/// Signal truth of one link at the start of one block: what an ideal receiver measures on
/// the direct (line-of-sight) signal. Reflected paths are not in `pseudorange_m` and
/// `carrier_phase_cycles`; their effect on an ideal tracking loop is given separately.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkTruth {
    /// The signal: the transmitter's, or at the observation level an observed-only signal
    /// of the same satellite ([`super::render::Synthesiser::with_observed`]).
    pub signal: Signal,
    /// Receive time in the receiver's clock (s since the scenario start): the block's
    /// first sample.
    pub t_s: f64,
    pub antenna: usize,
    /// Index of the transmitter in the synthesiser's list.
    pub tx: usize,
    /// c (receive time in receiver time - transmit time in satellite time) (m).
    pub pseudorange_m: f64,
    /// Accumulated carrier phase (cycles), RINEX sign (grows with the pseudorange); its
    /// integer ambiguity is zero by construction.
    pub carrier_phase_cycles: f64,
    /// Doppler (Hz), minus the rate of the carrier phase (event terms excluded).
    pub doppler_hz: f64,
    /// C/N0 of the direct path (dB-Hz), events included.
    pub cn0_dbhz: f64,
    /// Ionospheric group delay in the pseudorange (m); the carrier phase carries -iono_m.
    pub iono_m: f64,
    /// Tropospheric delay (m) in pseudorange and carrier phase.
    pub tropo_m: f64,
    /// Phase-centre offset + variation delay (m) in pseudorange and carrier phase.
    pub antenna_m: f64,
    /// Receiver clock offset times c (m) in pseudorange and carrier phase.
    pub rx_clock_m: f64,
    /// Satellite clock offset times c (m), subtracted from pseudorange and carrier phase.
    pub sat_clock_m: f64,
    /// Code-only delay of the active events (code step, ionospheric ramp) (m).
    pub event_code_m: f64,
    /// Carrier phase added by the active events (phase jump, ionospheric ramp) (cycles).
    pub event_carrier_cycles: f64,
    /// Code-tracking error the reflected paths cause in a non-coherent early-minus-late
    /// DLL with 1 chip spacing (m; Van Nee model).
    pub multipath_code_m: f64,
    /// Carrier-phase error the reflected paths cause in a receiver whose prompt
    /// correlator sits on the direct path (m, RINEX sign).
    pub multipath_carrier_m: f64,
}

/// A quantity linear in time across one geometry interval.
#[derive(Debug, Clone, Copy)]
struct Linear {
    t0: f64,
    v0: f64,
    rate: f64,
}

impl Linear {
    fn new(t0: f64, t1: f64, v0: f64, v1: f64) -> Self {
        Self {
            t0,
            v0,
            rate: (v1 - v0) / (t1 - t0),
        }
    }
    fn at(&self, t: f64) -> f64 {
        self.v0 + self.rate * (t - self.t0)
    }
}

/// A reflected path across one interval.
#[derive(Debug, Clone, Copy)]
struct ReflectionSegment {
    delay_m: Linear,
    relative_amplitude: Linear,
    phase_rad: Linear,
}

/// The direct path of one link at one true receive time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LinkState {
    /// `D_code` (module docs), s.
    pub code_delay_s: f64,
    /// `D_carr` (module docs), s.
    pub carrier_delay_s: f64,
    pub sat_clock_s: f64,
    pub iono_m: f64,
    pub tropo_m: f64,
    pub antenna_m: f64,
    pub cn0_dbhz: f64,
}

/// A link over one geometry interval: range by quintic Hermite interpolation, satellite
/// clock linear in transmit time, every other term linear in receive time.
#[derive(Debug, Clone)]
pub(crate) struct Segment {
    pub tx: usize,
    range: QuinticHermite,
    clock_t0_s: f64,
    clock_s: f64,
    drift: f64,
    iono_m: Linear,
    tropo_m: Linear,
    antenna_m: Linear,
    /// Each signal's phase-centre delay where the antenna has one per signal (else every
    /// signal's is `antenna_m`).
    antenna_by_signal_m: Vec<(Signal, Linear)>,
    cn0_dbhz: Linear,
    reflections: Vec<ReflectionSegment>,
}

impl Segment {
    /// The link `tx` between its ends `s` at `t0` and `e` at `t1`.
    pub fn new(tx: usize, t0: f64, t1: f64, s: &LinkEnd, e: &LinkEnd) -> Self {
        let lin = |a: f64, b: f64| Linear::new(t0, t1, a, b);
        Self {
            tx,
            range: QuinticHermite::new(
                t0,
                t1,
                [s.range_m, s.range_rate_mps, s.range_accel_mps2],
                [e.range_m, e.range_rate_mps, e.range_accel_mps2],
            ),
            clock_t0_s: t0 - s.range_m / C_MPS,
            clock_s: s.sat_clock_s,
            drift: s.sat_clock_drift,
            iono_m: lin(s.iono_m, e.iono_m),
            tropo_m: lin(s.tropo_m, e.tropo_m),
            antenna_m: lin(s.antenna_m, e.antenna_m),
            antenna_by_signal_m: (s.antenna_by_signal_m.iter())
                .zip(&e.antenna_by_signal_m)
                .map(|(&(signal, a), &(_, b))| (signal, lin(a, b)))
                .collect(),
            cn0_dbhz: lin(s.cn0_dbhz, e.cn0_dbhz),
            reflections: s
                .reflections
                .iter()
                .zip(&e.reflections)
                .map(|(a, b)| ReflectionSegment {
                    delay_m: lin(a.delay_m, b.delay_m),
                    relative_amplitude: lin(a.relative_amplitude, b.relative_amplitude),
                    phase_rad: lin(a.phase_rad, b.phase_rad),
                })
                .collect(),
        }
    }

    /// The direct path at true receive time `t`.
    pub fn at(&self, t: f64) -> LinkState {
        self.state(t, 1.0, &self.antenna_m)
    }

    /// The direct path at `t` of `signal`, another signal of the same satellite whose
    /// ionospheric delay is `iono_scale` times the link's (`(f_link / f)^2`, the first-order
    /// ionosphere), with its own phase-centre delay where the antenna has one per signal.
    pub fn at_scaled(&self, t: f64, iono_scale: f64, signal: Signal) -> LinkState {
        self.state(t, iono_scale, self.antenna_of(signal))
    }

    /// The direct path at `t`, the ionosphere scaled by `iono_scale`, the phase-centre
    /// delay `antenna`.
    fn state(&self, t: f64, iono_scale: f64, antenna: &Linear) -> LinkState {
        let tau = self.range.value(t) / C_MPS;
        let sat_clock_s = self.clock_s + self.drift * (t - tau - self.clock_t0_s);
        let (iono_m, tropo_m, antenna_m) = (
            iono_scale * self.iono_m.at(t),
            self.tropo_m.at(t),
            antenna.at(t),
        );
        LinkState {
            code_delay_s: tau + (iono_m + tropo_m + antenna_m) / C_MPS - sat_clock_s,
            carrier_delay_s: tau + (-iono_m + tropo_m + antenna_m) / C_MPS - sat_clock_s,
            sat_clock_s,
            iono_m,
            tropo_m,
            antenna_m,
            cn0_dbhz: self.cn0_dbhz.at(t),
        }
    }

    /// d D_carr / dt at `t` (s/s) of `signal`, the ionosphere scaled by `iono_scale`
    /// ([`Self::at_scaled`]).
    pub fn carrier_delay_rate(&self, t: f64, iono_scale: f64, signal: Signal) -> f64 {
        self.range.rate(t) / C_MPS - self.drift
            + (-iono_scale * self.iono_m.rate + self.tropo_m.rate + self.antenna_of(signal).rate)
                / C_MPS
    }

    /// The phase-centre delay of `signal` over the interval.
    fn antenna_of(&self, signal: Signal) -> &Linear {
        (self.antenna_by_signal_m.iter())
            .find(|(s, _)| *s == signal)
            .map_or(&self.antenna_m, |(_, l)| l)
    }

    /// The reflected paths at `t` (in the link's fixed order).
    pub fn reflections_at(&self, t: f64) -> impl Iterator<Item = Path> + '_ {
        self.reflections.iter().map(move |r| Path {
            delay_m: r.delay_m.at(t),
            relative_amplitude: r.relative_amplitude.at(t),
            phase_rad: r.phase_rad.at(t),
        })
    }

    /// Whether the link has reflected paths.
    pub fn has_reflections(&self) -> bool {
        !self.reflections.is_empty()
    }
}
