//! Sample file formats: interleaved little-endian complex `ci8`, `ci16`, `cf32`, and real
//! `ri8` for IF output, with their SigMF and GNSS-SDR names and full scale. The synthesiser
//! writes them; the receiver reads them.

/// A sample container.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SampleFormat {
    /// Complex, interleaved I/Q, signed 8-bit.
    Ci8,
    /// Complex, interleaved I/Q, signed 16-bit little-endian.
    Ci16,
    /// Complex, interleaved I/Q, 32-bit float little-endian.
    Cf32,
    /// Real, signed 8-bit (real IF).
    Ri8,
}

impl SampleFormat {
    /// Every container.
    pub const ALL: [SampleFormat; 4] = [
        SampleFormat::Ci8,
        SampleFormat::Ci16,
        SampleFormat::Cf32,
        SampleFormat::Ri8,
    ];

    /// The container named by a SigMF `core:datatype` (SigMF 1.0 "Dataset Format":
    /// `<r|c><type><bits>[_le|_be]`, no endianness suffix for 8-bit types) or a
    /// command-line spelling (`ci16`, `cf32`), any case; `None` for anything else
    /// (big-endian types included).
    pub fn from_name(name: &str) -> Option<Self> {
        match name.trim().to_ascii_lowercase().as_str() {
            "ci8" => Some(SampleFormat::Ci8),
            "ci16_le" | "ci16" => Some(SampleFormat::Ci16),
            "cf32_le" | "cf32" => Some(SampleFormat::Cf32),
            "ri8" => Some(SampleFormat::Ri8),
            _ => None,
        }
    }

    /// Container value that maps to 1.0 in decoded samples: `2^(bits-1)` for integers
    /// (exact in f32), 1 for float.
    pub fn full_scale(self) -> f32 {
        match self {
            SampleFormat::Ci8 | SampleFormat::Ri8 => 128.0,
            SampleFormat::Ci16 => 32768.0,
            SampleFormat::Cf32 => 1.0,
        }
    }

    /// Whether samples are complex (I/Q).
    pub fn is_complex(self) -> bool {
        !matches!(self, SampleFormat::Ri8)
    }
    /// Bytes per sample (both components for complex formats).
    pub fn bytes_per_sample(self) -> usize {
        match self {
            SampleFormat::Ci8 => 2,
            SampleFormat::Ci16 => 4,
            SampleFormat::Cf32 => 8,
            SampleFormat::Ri8 => 1,
        }
    }
    /// SigMF `core:datatype`.
    pub fn sigmf_datatype(self) -> &'static str {
        match self {
            SampleFormat::Ci8 => "ci8",
            SampleFormat::Ci16 => "ci16_le",
            SampleFormat::Cf32 => "cf32_le",
            SampleFormat::Ri8 => "ri8",
        }
    }
    /// GNSS-SDR `SignalSource.item_type`.
    pub fn gnss_sdr_item_type(self) -> &'static str {
        match self {
            SampleFormat::Ci8 => "ibyte",
            SampleFormat::Ci16 => "ishort",
            SampleFormat::Cf32 => "gr_complex",
            SampleFormat::Ri8 => "byte",
        }
    }
    /// Largest quantisation word length the container holds (bits); `None` for float.
    pub fn max_bits(self) -> Option<u8> {
        match self {
            SampleFormat::Ci8 | SampleFormat::Ri8 => Some(8),
            SampleFormat::Ci16 => Some(16),
            SampleFormat::Cf32 => None,
        }
    }
}

impl std::fmt::Display for SampleFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.sigmf_datatype())
    }
}
