//! Every value of a receiver configuration file has a range, checked when the file is
//! parsed: one message naming the file, the field, the value and the range (issue #33,
//! items 11 and 15). Before, `[tracking]` values were checked only when the receiver
//! started (and then named no file), and many had no range at all.

use skyforge_receiver::session::parse_config;

/// Each line of `cases`, alone in a file, is refused with a message holding `says`.
fn refused(cases: &[(&str, &str)]) {
    for (text, says) in cases {
        let e = parse_config(text, "rx.toml")
            .err()
            .unwrap_or_else(|| panic!("{text:?} accepted"))
            .to_string();
        assert!(e.starts_with("rx.toml: "), "{text:?}: {e}");
        assert!(e.contains(says), "{text:?}: {e}");
    }
}

#[test]
fn tracking_values_out_of_range_are_refused_at_parse_naming_the_file() {
    refused(&[
        (
            "[tracking]\npll_bandwidth_hz = 1e6\n",
            "tracking.pll_bandwidth_hz = 1000000: must be in [0.1, 100] Hz",
        ),
        (
            "[tracking]\nnarrow_early_late_spacing_chips = 1e-9\n",
            "tracking.narrow_early_late_spacing_chips = 1e-9: must be in [0.01, 2] chips",
        ),
        (
            "[tracking]\nslip_threshold_sigma = nan\n",
            "tracking.slip_threshold_sigma = NaN: must be in [1, 20] sigma",
        ),
        (
            "[tracking]\npll_lock_threshold = 5.0\n",
            "tracking.pll_lock_threshold = 5: must be in (0, 0.99]",
        ),
        (
            "[tracking]\ncn0_lock_threshold_dbhz = -1e300\n",
            "tracking.cn0_lock_threshold_dbhz = -1e300",
        ),
        (
            "[tracking]\nloss_of_lock_s = 1e300\n",
            "tracking.loss_of_lock_s",
        ),
        ("[tracking]\ncoherent_ms = 0\n", "tracking.coherent_ms = 0"),
        (
            "[tracking.bit_sync]\nmin_transitions = 0\n",
            "tracking.bit_sync.min_transitions = 0: must be in [1, 1000]",
        ),
        (
            "[tracking.bit_sync]\ndominance = 0.0\n",
            "tracking.bit_sync.dominance = 0",
        ),
        (
            "[tracking.bit_sync]\nnh_bits = 0\n",
            "tracking.bit_sync.nh_bits = 0",
        ),
        (
            "[tracking.ukf]\nq = [1e300, 0.0, 0.0, 0.0]\n",
            "tracking.ukf.q[0] = 1e300: must be in [0, 1e16]",
        ),
        (
            "[tracking.ukf]\ninitial_doppler_sigma_hz = 1e30\n",
            "tracking.ukf.initial_doppler_sigma_hz = 1e30",
        ),
    ]);
}

#[test]
fn pvt_and_assist_values_out_of_range_are_refused() {
    refused(&[
        (
            "[pvt]\nraim_pmd = 1e-300\n",
            "pvt.raim_pmd = 1e-300: must be in [1e-12, 0.5] (or 0: off)",
        ),
        ("[pvt]\nraim_hal_m = 1e300\n", "pvt.raim_hal_m = 1e300"),
        (
            "[assist]\nposition_ecef_m = [0.0, 0.0, 0.0]\n",
            "assist.position_ecef_m = [0, 0, 0] (radius 0 m): must lie at a radius in \
             [6355000, 1e8] m from the Earth's centre",
        ),
        (
            "[assist]\nposition_ecef_m = [1e30, 0.0, 0.0]\n",
            "assist.position_ecef_m = [1e30, 0, 0]",
        ),
        (
            "[assist]\nposition_ecef_m = [6378137.0, 0.0, 0.0]\nvelocity_ecef_mps = [1e300, 0.0, 0.0]\n",
            "assist.velocity_ecef_mps[0] = 1e300",
        ),
        (
            "[assist]\nposition_ecef_m = [6378137.0, 0.0, 0.0]\noscillator_ppm = 1e9\n",
            "assist.oscillator_ppm = 1e9: must be in [0, 1000] ppm",
        ),
    ]);
}

/// The defaults, the documented example values and `synth`'s assistance stay accepted.
#[test]
fn the_defaults_and_the_written_assistance_are_in_range() {
    let assist = skyforge_receiver::pipeline::assistance_toml(
        &nalgebra::Vector3::new(6_878_137.0, 0.0, 0.0),
        &nalgebra::Vector3::new(0.0, 7600.0, 0.0),
    );
    for text in [
        "",
        assist.as_str(),
        "[tracking]\npll_narrow_bandwidth_hz = 2.0\nfll_assist_s = inf\ncoherent_ms = 20\n",
        "[stages]\ncarrier = \"ukf\"\n[tracking.ukf]\nq = [1e-10, 1e-4, 1e2, 1e8]\n",
        "[tracking.ukf]\nq = [1e-5, 10.0, 1e7, 1e13]\n",
        "[pvt]\nraim_pfa = 0.0\nraim_pmd = 0.0\n",
    ] {
        assert!(parse_config(text, "rx.toml").is_ok(), "{text}");
    }
}
