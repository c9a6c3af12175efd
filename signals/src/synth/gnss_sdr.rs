//! A ready-to-run GNSS-SDR configuration for one antenna's recording (GNSS-SDR 0.0.17
//! option names: File_Signal_Source, PCPS acquisition, DLL/PLL tracking, telemetry
//! decoders, hybrid observables, RTKLIB single-point PVT).
//!
//! Known GNSS-SDR 0.0.17 limitation: its B1I code generator produces replicas for PRN
//! 1-33 only (for a higher PRN it returns without writing a code, so acquisition
//! correlates against zeros); BeiDou satellites C34-C63 in a recording are never acquired.
//! It decodes D2 (GEO) navigation data for C01-C05. The `.conf` says so in a comment.
//! GNSS-SDR 0.0.17 has no BeiDou B2a blocks (acquisition, tracking or B-CNAV2 telemetry):
//! B2a is left out of the `.conf`, which says so in a comment.

use super::config::SignalConfig;
use skyforge_gnss::sample_format::SampleFormat;
use skyforge_gnss::signal::Signal;
use std::fmt::Write;

/// Highest BeiDou PRN for which GNSS-SDR 0.0.17 generates a B1I replica (read from the
/// Debian binary: its generator rejects PRN - 1 > 32 before looking up the phase table).
pub const GNSS_SDR_0017_BDS_PRN_MAX: u8 = 33;

/// B1I channels: enough for every BDS-2 satellite in view over Asia (up to 15).
const BDS_CHANNELS: usize = 16;
/// E5a channels: Galileo satellites in view (up to about 12 of 24-30).
const GAL_CHANNELS: usize = 12;
/// L5 channels: GPS satellites in view (up to about 12 of 31).
const GPS_L5_CHANNELS: usize = 12;
/// E1 channels: as E5a's.
const GAL_E1_CHANNELS: usize = GAL_CHANNELS;

/// The corrections GNSS-SDR's PVT applies: those of the errors in the signal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PvtCorrections {
    /// The broadcast (Klobuchar) ionosphere.
    pub broadcast_iono: bool,
    /// The Saastamoinen troposphere.
    pub troposphere: bool,
}

/// Acquisition Doppler search written into the configuration (Hz): ground / LEO.
const DOPPLER_MAX_GROUND_HZ: f64 = 5_000.0;
const DOPPLER_MAX_LEO_HZ: f64 = 50_000.0;

/// The `.conf` text of the recording `name` (`<name>.sigmf-data`, PVT outputs
/// `<name>.*`) of `signals` (one, or the signals of one band: GNSS-SDR's channels of
/// each on one signal source): a LEO gets a widened Doppler search and no atmospheric
/// corrections (it flies above the troposphere and mostly above the ionosphere); a ground
/// receiver corrects the errors the signal carries (`iono_on`, `tropo_on`).
pub fn recording_config(
    cfg: &SignalConfig,
    name: &str,
    signals: &[Signal],
    leo: bool,
    iono_on: bool,
    tropo_on: bool,
) -> String {
    let doppler = if leo {
        DOPPLER_MAX_LEO_HZ
    } else {
        DOPPLER_MAX_GROUND_HZ
    };
    let corrections = PvtCorrections {
        broadcast_iono: iono_on && !leo,
        troposphere: tropo_on && !leo,
    };
    config(
        cfg,
        &format!("{name}.sigmf-data"),
        signals,
        doppler,
        corrections,
        name,
    )
}

/// The `.conf` text for `data_file` (a path GNSS-SDR opens relative to its working
/// directory) holding `signals` (those GNSS-SDR has no block for are left out);
/// `doppler_max_hz` widens acquisition for high dynamics; `corrections` are
/// turned on in the PVT; PVT outputs go to `output_prefix.*`.
pub fn config(
    cfg: &SignalConfig,
    data_file: &str,
    signals: &[Signal],
    doppler_max_hz: f64,
    corrections: PvtCorrections,
    output_prefix: &str,
) -> String {
    let fs = cfg.sample_rate_hz.round() as u64;
    let adapter = match cfg.format {
        SampleFormat::Ci8 => "Ibyte_To_Complex",
        SampleFormat::Ci16 => "Ishort_To_Complex",
        SampleFormat::Cf32 | SampleFormat::Ri8 => "Pass_Through",
    };
    let mut s = String::new();
    let mut line = |text: &str| {
        let _ = writeln!(s, "{text}");
    };
    line("; GNSS-SDR configuration written by SkyForge for one antenna's recording.");
    line("[GNSS-SDR]");
    line(&format!("GNSS-SDR.internal_fs_sps={fs}"));
    line("SignalSource.implementation=File_Signal_Source");
    line(&format!("SignalSource.filename={data_file}"));
    line(&format!(
        "SignalSource.item_type={}",
        cfg.format.gnss_sdr_item_type()
    ));
    line(&format!("SignalSource.sampling_frequency={fs}"));
    line("SignalSource.samples=0");
    line("SignalSource.repeat=false");
    line("SignalSource.dump=false");
    line("SignalSource.enable_throttle_control=false");
    line("SignalConditioner.implementation=Signal_Conditioner");
    line(&format!("DataTypeAdapter.implementation={adapter}"));
    if cfg.format == SampleFormat::Ri8 || cfg.if_hz != 0.0 {
        line("InputFilter.implementation=Freq_Xlating_Fir_Filter");
        line(&format!(
            "InputFilter.input_item_type={}",
            if cfg.format == SampleFormat::Ri8 {
                "byte"
            } else {
                "gr_complex"
            }
        ));
        line("InputFilter.output_item_type=gr_complex");
        line("InputFilter.taps_item_type=float");
        line("InputFilter.number_of_taps=5");
        line("InputFilter.number_of_bands=2");
        line("InputFilter.band1_begin=0.0");
        line("InputFilter.band1_end=0.45");
        line("InputFilter.band2_begin=0.55");
        line("InputFilter.band2_end=1.0");
        line("InputFilter.ampl1_begin=1.0");
        line("InputFilter.ampl1_end=1.0");
        line("InputFilter.ampl2_begin=0.0");
        line("InputFilter.ampl2_end=0.0");
        line("InputFilter.band1_error=1.0");
        line("InputFilter.band2_error=1.0");
        line("InputFilter.filter_type=bandpass");
        line("InputFilter.grid_density=16");
        line(&format!("InputFilter.sampling_frequency={fs}"));
        line(&format!("InputFilter.IF={}", cfg.if_hz));
    } else {
        line("InputFilter.implementation=Pass_Through");
        line("InputFilter.item_type=gr_complex");
    }
    line("Resampler.implementation=Pass_Through");
    line("Resampler.item_type=gr_complex");
    line("Channels.in_acquisition=1");
    if signals.contains(&Signal::GpsL1Ca) {
        channel_lines(&mut line, &GPS_L1CA_BLOCKS, doppler_max_hz);
    }
    if signals.contains(&Signal::BdsB1I) {
        line(&format!(
            "; GNSS-SDR 0.0.17 has B1I replicas for PRN 1-{GNSS_SDR_0017_BDS_PRN_MAX} only: C{:02}-C63 are not acquired.",
            GNSS_SDR_0017_BDS_PRN_MAX + 1
        ));
        // GEO + IGSO + MEO over Asia: more satellites in view than GPS.
        line(&format!("Channels_B1.count={BDS_CHANNELS}"));
        line("Acquisition_B1.implementation=BEIDOU_B1I_PCPS_Acquisition");
        line("Acquisition_B1.item_type=gr_complex");
        line("Acquisition_B1.coherent_integration_time_ms=1");
        line("Acquisition_B1.pfa=0.01");
        line(&format!(
            "Acquisition_B1.doppler_max={}",
            doppler_max_hz.round()
        ));
        // Every 1 ms B1I code period carries an NH chip (D1, 1 kbit/s) or half a D2 bit
        // (500 bit/s), so a 1 ms acquisition window holds a sign change half of the time,
        // which splits the correlation peak into two Doppler lobes some 700 Hz either side
        // of the true Doppler. Measured with 0.0.17 on interop-bds-static: 4 of 19 positive
        // acquisitions 800-960 Hz off, each ending in a loss of lock 5-10 s later. With
        // bit_transition_flag GNSS-SDR correlates two consecutive windows and keeps the
        // better one (max_dwells must be 1); the 125 Hz step keeps the initial frequency
        // error within what the 25 Hz PLL pulls in.
        line("Acquisition_B1.doppler_step=125");
        line("Acquisition_B1.bit_transition_flag=true");
        line("Acquisition_B1.max_dwells=1");
        line("Tracking_B1.implementation=BEIDOU_B1I_DLL_PLL_Tracking");
        line("Tracking_B1.item_type=gr_complex");
        line("Tracking_B1.pll_bw_hz=25.0");
        line("Tracking_B1.dll_bw_hz=2.0");
        line("TelemetryDecoder_B1.implementation=BEIDOU_B1I_Telemetry_Decoder");
    }
    if signals.contains(&Signal::GalE5a) {
        channel_lines(&mut line, &GAL_E5A_BLOCKS, doppler_max_hz);
    }
    if signals.contains(&Signal::GpsL5) {
        channel_lines(&mut line, &GPS_L5_BLOCKS, doppler_max_hz);
    }
    if signals.contains(&Signal::GalE1) {
        channel_lines(&mut line, &GAL_E1_BLOCKS, doppler_max_hz);
    }
    if signals.contains(&Signal::BdsB2a) {
        line("; GNSS-SDR 0.0.17 has no BeiDou B2a blocks: B2a is left out of this configuration.");
    }
    if signals.contains(&Signal::BdsB1C) {
        line("; GNSS-SDR 0.0.17 has no BeiDou B1C blocks: B1C is left out of this configuration.");
    }
    line("Observables.implementation=Hybrid_Observables");
    line("PVT.implementation=RTKLIB_PVT");
    line("PVT.positioning_mode=Single");
    line("PVT.elevation_mask=10");
    line(if corrections.broadcast_iono {
        "PVT.iono_model=Broadcast"
    } else {
        "PVT.iono_model=OFF"
    });
    line(if corrections.troposphere {
        "PVT.trop_model=Saastamoinen"
    } else {
        "PVT.trop_model=OFF"
    });
    line("PVT.output_rate_ms=1000");
    line("PVT.display_rate_ms=1000");
    line(&format!("PVT.nmea_dump_filename={output_prefix}.nmea"));
    line("PVT.flag_nmea_tty_port=false");
    line("PVT.flag_rtcm_server=false");
    line("PVT.flag_rtcm_tty_port=false");
    line("PVT.output_enabled=true");
    line("PVT.dump=false");
    s
}

/// One signal's GNSS-SDR channel blocks: PCPS acquisition over one code period with a 250
/// Hz step and two dwells, DLL/PLL tracking (2 Hz DLL), the telemetry decoder.
struct ChannelBlocks {
    /// GNSS-SDR's channel code (`1C`, `5X`, `L5`, `1B`).
    code: &'static str,
    channels: usize,
    acquisition: &'static str,
    /// Coherent integration of acquisition (ms): one code period.
    coherent_ms: u32,
    /// Acquisition Doppler step (Hz).
    doppler_step_hz: u32,
    /// Acquire on the pilot component (GNSS-SDR's `acquire_pilot`, where it has one).
    acquire_pilot: bool,
    tracking: &'static str,
    /// Track the pilot (its secondary code synchronised), data from the other component.
    track_pilot: bool,
    pll_bw_hz: &'static str,
    /// Early-late spacing (chips), and the very-early-late one of a VEML tracking (BOC).
    early_late_chips: &'static str,
    very_early_late_chips: Option<&'static str>,
    /// Bandwidth (Hz) of a frequency-locked loop that pulls the carrier in before the PLL
    /// takes over, where the tracking needs one.
    fll_pull_in_hz: Option<&'static str>,
    telemetry: &'static str,
}

/// GPS L1 C/A (channel code 1C).
const GPS_L1CA_BLOCKS: ChannelBlocks = ChannelBlocks {
    code: "1C",
    channels: 12,
    acquisition: "GPS_L1_CA_PCPS_Acquisition",
    coherent_ms: 1,
    doppler_step_hz: 250,
    acquire_pilot: false,
    tracking: "GPS_L1_CA_DLL_PLL_Tracking",
    track_pilot: false,
    pll_bw_hz: "25.0",
    early_late_chips: "0.5",
    very_early_late_chips: None,
    fll_pull_in_hz: None,
    telemetry: "GPS_L1_CA_Telemetry_Decoder",
};

/// Galileo E5a (channel code 5X): acquisition and tracking on the E5a-Q pilot, whose
/// 100-chip secondary code the tracking synchronises to; F/NAV decoded from E5a-I.
const GAL_E5A_BLOCKS: ChannelBlocks = ChannelBlocks {
    code: "5X",
    channels: GAL_CHANNELS,
    acquisition: "Galileo_E5a_Pcps_Acquisition",
    coherent_ms: 1,
    doppler_step_hz: 250,
    acquire_pilot: true,
    tracking: "Galileo_E5a_DLL_PLL_Tracking",
    track_pilot: true,
    pll_bw_hz: "20.0",
    early_late_chips: "0.5",
    very_early_late_chips: None,
    fll_pull_in_hz: None,
    telemetry: "Galileo_E5a_Telemetry_Decoder",
};

/// GPS L5 (channel code L5): acquisition on I5 and tracking on the Q5 pilot, whose
/// 20-chip Neumann-Hoffman code the tracking synchronises to; CNAV decoded from I5.
const GPS_L5_BLOCKS: ChannelBlocks = ChannelBlocks {
    code: "L5",
    channels: GPS_L5_CHANNELS,
    acquisition: "GPS_L5i_PCPS_Acquisition",
    coherent_ms: 1,
    doppler_step_hz: 250,
    acquire_pilot: false,
    tracking: "GPS_L5_DLL_PLL_Tracking",
    track_pilot: true,
    pll_bw_hz: "20.0",
    early_late_chips: "0.5",
    very_early_late_chips: None,
    fll_pull_in_hz: None,
    telemetry: "GPS_L5_Telemetry_Decoder",
};

/// Galileo E1 (channel code 1B): acquisition over the 4 ms code on the E1-C pilot with a
/// BOC(1,1) replica, very-early-minus-late tracking on the pilot (0.15-chip early-late
/// spacing inside the BOC correlation's central peak, 0.6-chip very-early-late to watch
/// its side peaks), its 25-chip secondary code synchronised; I/NAV decoded from E1-B.
/// The 4 ms acquisition's Doppler bins are 1/(2 x 4 ms) = 125 Hz wide, and a 10 Hz FLL
/// pulls the carrier in before the 15 Hz PLL: measured with 0.0.17 on 50 s of
/// `interop-e1-static` (by hand, 2026-11-30), 250 Hz steps without the FLL left 8 of 9
/// satellites unsynchronised to CS25 (GNSS-SDR drops them after 20 s), 125 Hz steps 4 of
/// 9, 125 Hz with the FLL 1 of 9.
const GAL_E1_BLOCKS: ChannelBlocks = ChannelBlocks {
    code: "1B",
    channels: GAL_E1_CHANNELS,
    acquisition: "Galileo_E1_PCPS_Ambiguous_Acquisition",
    coherent_ms: 4,
    doppler_step_hz: 125,
    acquire_pilot: true,
    tracking: "Galileo_E1_DLL_PLL_VEML_Tracking",
    track_pilot: true,
    pll_bw_hz: "15.0",
    early_late_chips: "0.15",
    very_early_late_chips: Some("0.6"),
    fll_pull_in_hz: Some("10.0"),
    telemetry: "Galileo_E1B_Telemetry_Decoder",
};

/// The `.conf` lines of `b`, searching Doppler to +-`doppler_max_hz`.
fn channel_lines(line: &mut impl FnMut(&str), b: &ChannelBlocks, doppler_max_hz: f64) {
    let c = b.code;
    line(&format!("Channels_{c}.count={}", b.channels));
    line(&format!("Acquisition_{c}.implementation={}", b.acquisition));
    line(&format!("Acquisition_{c}.item_type=gr_complex"));
    line(&format!(
        "Acquisition_{c}.coherent_integration_time_ms={}",
        b.coherent_ms
    ));
    if b.acquire_pilot {
        line(&format!("Acquisition_{c}.acquire_pilot=true"));
    }
    line(&format!("Acquisition_{c}.pfa=0.01"));
    line(&format!(
        "Acquisition_{c}.doppler_max={}",
        doppler_max_hz.round()
    ));
    line(&format!(
        "Acquisition_{c}.doppler_step={}",
        b.doppler_step_hz
    ));
    line(&format!("Acquisition_{c}.max_dwells=2"));
    line(&format!("Tracking_{c}.implementation={}", b.tracking));
    line(&format!("Tracking_{c}.item_type=gr_complex"));
    if b.track_pilot {
        line(&format!("Tracking_{c}.track_pilot=true"));
    }
    line(&format!("Tracking_{c}.pll_bw_hz={}", b.pll_bw_hz));
    line(&format!("Tracking_{c}.dll_bw_hz=2.0"));
    if let Some(fll) = b.fll_pull_in_hz {
        line(&format!("Tracking_{c}.enable_fll_pull_in=true"));
        line(&format!("Tracking_{c}.fll_bw_hz={fll}"));
    }
    line(&format!(
        "Tracking_{c}.early_late_space_chips={}",
        b.early_late_chips
    ));
    if let Some(spacing) = b.very_early_late_chips {
        line(&format!(
            "Tracking_{c}.very_early_late_space_chips={spacing}"
        ));
    }
    line(&format!(
        "TelemetryDecoder_{c}.implementation={}",
        b.telemetry
    ));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bds_conf() -> String {
        let cfg = SignalConfig {
            sample_rate_hz: 4e6,
            if_hz: 0.0,
            format: SampleFormat::Ci8,
            bits: Some(8),
            cn0_dbhz: 45.0,
            truth_rate_hz: 1000,
            ..SignalConfig::default()
        };
        let corrections = PvtCorrections {
            broadcast_iono: true,
            troposphere: true,
        };
        config(
            &cfg,
            "a.sigmf-data",
            &[Signal::BdsB1I],
            5000.0,
            corrections,
            "a",
        )
    }

    /// A B2a recording: GNSS-SDR 0.0.17 has no block for it, so no channel, and the
    /// `.conf` says why.
    #[test]
    fn b2a_is_left_out_and_the_conf_says_so() {
        let cfg = SignalConfig {
            sample_rate_hz: 20.46e6,
            ..SignalConfig::default()
        };
        let corrections = PvtCorrections {
            broadcast_iono: true,
            troposphere: true,
        };
        let conf = config(
            &cfg,
            "a.sigmf-data",
            &[Signal::BdsB2a],
            5000.0,
            corrections,
            "a",
        );
        assert!(!conf.contains("Channels_"), "{conf}");
        assert!(conf.contains("no BeiDou B2a blocks"), "{conf}");
        let conf = config(
            &SignalConfig {
                sample_rate_hz: 15e6,
                ..SignalConfig::default()
            },
            "b.sigmf-data",
            &[Signal::BdsB1C],
            5000.0,
            corrections,
            "b",
        );
        assert!(!conf.contains("Channels_"), "{conf}");
        assert!(conf.contains("no BeiDou B1C blocks"), "{conf}");
    }

    /// GNSS-SDR's INI reader takes `;` comments, `[section]` headers and `key=value`.
    #[test]
    fn every_line_is_a_comment_a_section_or_a_key_value_pair() {
        for l in bds_conf().lines() {
            let ok = l.starts_with(';')
                || (l.starts_with('[') && l.ends_with(']'))
                || l.split_once('=')
                    .is_some_and(|(k, v)| !k.is_empty() && !v.is_empty());
            assert!(ok, "{l}");
        }
    }

    /// The embedded BDS-2 set has 15 satellites, all of which may be in view over Asia.
    #[test]
    fn beidou_has_a_channel_for_every_bds2_satellite_and_states_the_prn_limit() {
        let conf = bds_conf();
        let count: usize = conf
            .lines()
            .find_map(|l| l.strip_prefix("Channels_B1.count="))
            .and_then(|v| v.parse().ok())
            .unwrap_or(0);
        assert!(count >= 15, "{count} channels");
        assert!(conf.contains("PRN 1-33 only"));
    }
}
