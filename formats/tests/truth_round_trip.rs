//! `truth.h5` written by the one writer and read back by the one reader: every value the
//! reader offers comes back as written, and a malformed file is refused with the file and
//! the dataset named.

use hifitime::Epoch;
use nalgebra::{Matrix3, Rotation3, UnitQuaternion};
use skyforge_formats::truth::{
    DOPPLER_ACCEL_HZPS2, DOPPLER_HZ, DOPPLER_RATE_HZPS, NOMINAL_BODY_ATTR, RunMeta, TRUE_BODY_ATTR,
    TruthFile, TruthWriter,
};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_orbits::platform::PlatformState;
use skyforge_signals::antenna::Antenna;
use skyforge_signals::truth::{GeometryChunk, LinkGeometry};
use std::path::Path;

const SATS: usize = 3;

fn antenna(name: &str, x: f64) -> Antenna {
    Antenna {
        name: name.into(),
        nominal_body_m: Vec3::new(x, 0.5, -0.25),
        true_body_m: Vec3::new(x + 0.001, 0.5, -0.25),
        boresight_body: Vec3::new(0.0, 0.0, -1.0),
        fov_half_angle_rad: 1.4,
        elevation_mask_rad: 0.1,
        pco_m: Vec3::new(0.0, 0.0, 0.05),
        pcv_m: None,
        gain_dbi: None,
        phase_centres: Vec::new(),
    }
}

/// Whether satellite `s` is in view of antenna `a` at epoch `k`: a pattern with gaps.
fn in_view(k: usize, a: usize, s: usize) -> bool {
    !(k + 2 * a + s).is_multiple_of(3)
}

/// Epochs `first..first + n` of a platform turning about Z, with link values that encode
/// (epoch, antenna, satellite).
fn chunk(first: usize, n: usize, antennas: usize) -> GeometryChunk {
    let mut links = Vec::new();
    for k in first..first + n {
        for a in 0..antennas {
            for s in 0..SATS {
                let code = (100 * k + 10 * a + s) as f64;
                links.push(if in_view(k, a, s) {
                    LinkGeometry {
                        visible: true,
                        doppler_hz: code,
                        doppler_rate_hzps: code + 0.25,
                        doppler_accel_hzps2: code + 0.5,
                        ..LinkGeometry::NOT_VISIBLE
                    }
                } else {
                    LinkGeometry::NOT_VISIBLE
                });
            }
        }
    }
    GeometryChunk {
        t_s: (first..first + n).map(|k| 0.5 * k as f64).collect(),
        platform: (first..first + n)
            .map(|k| PlatformState {
                r_ecef_m: Vec3::new(7.0e6 + k as f64, -1.0e3, 2.5e3),
                v_ecef_mps: Vec3::new(0.0, 7.5e3, 0.0),
                c_body_ecef: rotation(k),
                attitude: YawPitchRoll::default(),
            })
            .collect(),
        links,
        n_antennas: antennas,
        n_satellites: SATS,
    }
}

fn rotation(k: usize) -> Matrix3<f64> {
    Rotation3::from_euler_angles(0.1, -0.2, 0.05 * k as f64).into_inner()
}

fn meta() -> RunMeta {
    RunMeta {
        scenario: "round-trip".into(),
        source: "inline".into(),
        text: "name = \"round-trip\"\n".into(),
        start_epoch: "2024-03-01T00:00:00 GPST".into(),
        seed: 7,
        step_s: 0.5,
        satellite_errors: false,
    }
}

fn write(path: &Path, antennas: &[Antenna]) {
    let sats = [SatId::gps(5), SatId::gps(12), SatId::beidou(19)];
    let mut w = TruthWriter::create(path, &meta(), &sats, antennas).unwrap();
    w.append(&chunk(0, 4, antennas.len())).unwrap();
    w.append(&chunk(4, 3, antennas.len())).unwrap();
    w.finish().unwrap();
}

#[test]
fn what_the_writer_writes_the_reader_reads() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("truth.h5");
    let antennas = [antenna("ant1", 0.0), antenna("ant2", 1.0)];
    write(&path, &antennas);

    let file = TruthFile::open(&path).unwrap();
    assert_eq!(file.scenario_name().unwrap(), "round-trip");
    assert_eq!(file.scenario_toml().unwrap(), meta().text);
    let start: Epoch = "2024-03-01T00:00:00 GPST".parse().unwrap();
    assert_eq!(file.start_epoch().unwrap(), start);
    let epochs = 7;
    let t_s: Vec<f64> = (0..epochs).map(|k| 0.5 * k as f64).collect();
    assert_eq!(file.times(100).unwrap(), t_s);
    assert_eq!(file.satellite_ids(100).unwrap(), ["G05", "G12", "C19"]);
    assert_eq!(file.antenna_names().unwrap(), ["ant1", "ant2"]);

    let platform = file.platform(100).unwrap();
    assert_eq!(platform.t_s, t_s);
    for k in 0..epochs {
        assert_eq!(
            platform.r_ecef_m[k],
            Vec3::new(7.0e6 + k as f64, -1.0e3, 2.5e3)
        );
        let expected = UnitQuaternion::from_matrix(&rotation(k));
        assert!(platform.q_body_ecef[k].angle_to(&expected) < 1e-12, "{k}");
    }

    for (a, ant) in antennas.iter().enumerate() {
        let nominal = file.antenna_vector(&ant.name, NOMINAL_BODY_ATTR).unwrap();
        let true_m = file.antenna_vector(&ant.name, TRUE_BODY_ATTR).unwrap();
        assert_eq!(Vec3::from(nominal), ant.nominal_body_m);
        assert_eq!(Vec3::from(true_m), ant.true_body_m);
        let visible = file.visible(&ant.name, epochs, SATS, 1000).unwrap();
        let links = file.links(&ant.name, epochs, SATS, 1000).unwrap();
        let mut expected_links = (Vec::new(), Vec::new());
        for k in 0..epochs {
            for s in 0..SATS {
                assert_eq!(visible[k * SATS + s], u8::from(in_view(k, a, s)));
                if in_view(k, a, s) {
                    expected_links.0.push(k as u32);
                    expected_links.1.push(s as u16);
                }
            }
        }
        assert_eq!((links.epoch.clone(), links.sat.clone()), expected_links);
        for (name, add) in [
            (DOPPLER_HZ, 0.0),
            (DOPPLER_RATE_HZPS, 0.25),
            (DOPPLER_ACCEL_HZPS2, 0.5),
        ] {
            let values = file.link_values(&ant.name, name, &links).unwrap();
            let expected: Vec<f64> = links
                .epoch
                .iter()
                .zip(&links.sat)
                .map(|(&k, &s)| (100 * k as usize + 10 * a + s as usize) as f64 + add)
                .collect();
            assert_eq!(values, expected, "{name}");
        }
    }
}

#[test]
fn bounds_and_missing_parts_are_refused_naming_the_file_and_the_dataset() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("truth.h5");
    write(&path, &[antenna("ant1", 0.0)]);
    let file = TruthFile::open(&path).unwrap();
    let shown = |e: skyforge_formats::FormatError| e.to_string();
    let e = shown(file.platform(6).unwrap_err());
    assert!(
        e.contains("truth.h5") && e.contains("time/t_s") && e.contains("at most 6"),
        "{e}"
    );
    let e = shown(file.times(3).unwrap_err());
    assert!(e.contains("time/t_s") && e.contains("at most 3"), "{e}");
    let e = shown(file.antenna_vector("ant9", NOMINAL_BODY_ATTR).unwrap_err());
    assert!(e.contains("antenna ant9 attribute nominal_body_m"), "{e}");
    let e = shown(file.visible("ant1", 7, 4, 1000).unwrap_err());
    assert!(e.contains("antennas/ant1/visible has 21 values"), "{e}");
    let e = shown(file.links("ant1", 2, 3, 1000).unwrap_err());
    assert!(e.contains("do not index"), "{e}");
    let e = shown(TruthFile::open(&dir.path().join("none.h5")).unwrap_err());
    assert!(e.contains("none.h5"), "{e}");
    std::fs::write(dir.path().join("text.h5"), "not hdf5").unwrap();
    let e = shown(TruthFile::open(&dir.path().join("text.h5")).unwrap_err());
    assert!(e.contains("not readable as HDF5"), "{e}");
}
