//! The receiver file's `[pvt]` table: the protection settings of RAIM (navigation::pvt)
//! as a receiver.toml sets them, and the refusal of bad ones.

use skyforge_receiver::pipeline::ReceiverFile;
#[test]
fn the_receiver_file_sets_the_protection_settings_and_refuses_bad_ones() {
    let parse = |text: &str| toml::from_str::<ReceiverFile>(text).unwrap().resolve();
    let (cfg, _) =
        parse("[pvt]\nraim_pmd = 1e-4\nraim_hal_m = 1000.0\nraim_val_m = 35.0\n").unwrap();
    assert_eq!(cfg.pvt.raim_pmd, 1e-4);
    assert_eq!(cfg.pvt.raim_hal_m, 1000.0);
    assert_eq!(cfg.pvt.raim_val_m, Some(35.0));
    let (cfg, _) = parse("").unwrap();
    assert_eq!(cfg.pvt, skyforge_navigation::pvt::PvtConfig::default());
    for (text, field) in [
        ("[pvt]\nraim_pmd = 1.5\n", "pvt.raim_pmd"),
        ("[pvt]\nraim_hal_m = -1.0\n", "pvt.raim_hal_m"),
        ("[pvt]\nraim_val_m = 0.0\n", "pvt.raim_val_m"),
    ] {
        let e = parse(text).unwrap_err();
        assert_eq!(e.field, field, "{text}");
    }
}
