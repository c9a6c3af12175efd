#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| skyforge_fuzz_targets::rinex_obs(data));
