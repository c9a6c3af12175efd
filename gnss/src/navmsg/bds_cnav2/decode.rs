//! Receiving B-CNAV2: one frame from its soft symbols (preamble polarity, LDPC decoding,
//! CRC-24Q, fields) and the assembly of message types 10, 11 and 30 into an ephemeris.
//!
//! Soft symbols: positive = logic 0, negative = logic 1, magnitude the confidence, 0 an
//! erasure.

use super::layout::{self, CNAV2_FRAME_SYMBOLS, CNAV2_PREAMBLE, FRAME_BITS, PREAMBLE_SYMBOLS};
use crate::navmsg::bds_cnav_eph::{self as e};
use crate::navmsg::crc24q::crc24q_bits;
use crate::navmsg::field::{Field, Fields, read_fields};
use crate::navmsg::ldpc_gf64::B2A_FRAME;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId};

/// Min-sum iterations before a frame is given up.
const LDPC_ITERATIONS: usize = 30;

/// One decoded frame: header and, for the types SkyForge builds (10, 11, 30, 34), the
/// raw data fields (LSB units, two's complement fields sign-extended).
#[derive(Debug, Clone, PartialEq)]
pub struct Cnav2Message {
    pub prn: u8,
    pub mes_type: u8,
    /// BDT seconds of week of the frame's first preamble symbol.
    pub sow_s: u32,
    fields: Fields,
}

impl Cnav2Message {
    /// The raw value of data field `name` (e.g. "IODE", "toe", "a0"), if the type has it.
    pub fn field(&self, name: &str) -> Option<i64> {
        let fields = layout::data_fields(self.mes_type)?;
        fields
            .iter()
            .find(|f| f.name == name)
            .map(|f| self.fields.get(f))
    }

    fn get(&self, f: &Field) -> i64 {
        self.fields.get(f)
    }
}

/// Why soft symbols are not a B-CNAV2 frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum Cnav2DecodeError {
    #[error("a B-CNAV2 frame is 600 soft symbols, got {0}")]
    Length(usize),
    #[error("the symbols do not start with the preamble 0xE24DE8 (inverted: {inverted})")]
    Preamble { inverted: bool },
    #[error("the LDPC(96, 48) decoder found no codeword")]
    Ldpc,
    #[error("CRC-24Q mismatch")]
    Crc,
}

/// Decode one frame from its 600 soft symbols (polarity as received): the preamble must
/// agree in at least 20 of 24 hard decisions.
pub fn decode_frame(soft: &[f32]) -> Result<Cnav2Message, Cnav2DecodeError> {
    if soft.len() != CNAV2_FRAME_SYMBOLS {
        return Err(Cnav2DecodeError::Length(soft.len()));
    }
    let agree = soft[..PREAMBLE_SYMBOLS]
        .iter()
        .enumerate()
        .filter(|&(k, &s)| {
            let bit = (CNAV2_PREAMBLE >> (PREAMBLE_SYMBOLS - 1 - k)) & 1;
            (bit == 1) == (s < 0.0)
        })
        .count();
    if agree < 20 {
        return Err(Cnav2DecodeError::Preamble {
            inverted: agree <= 4,
        });
    }
    let bits = B2A_FRAME
        .decode_soft(&soft[PREAMBLE_SYMBOLS..], LDPC_ITERATIONS)
        .ok_or(Cnav2DecodeError::Ldpc)?;
    debug_assert_eq!(bits.len(), FRAME_BITS);
    if crc24q_bits(&bits) != 0 {
        return Err(Cnav2DecodeError::Crc);
    }
    let header = read_fields(&bits, &layout::HEADER);
    let mes_type = header[1] as u8;
    let mut fields = Fields::default();
    if let Some(data) = layout::data_fields(mes_type) {
        fields.absorb(&data, &read_fields(&bits[30..], &data));
    }
    Ok(Cnav2Message {
        prn: header[0] as u8,
        mes_type,
        sow_s: header[2] as u32 * 3,
        fields,
    })
}

/// Collects message types 10, 11 and 30 of one satellite into an ephemeris: a type 10
/// and the type 11 of the next frame, and a type 30 whose IODC's 8 LSBs equal the IODE
/// (§7.4.3).
#[derive(Debug, Clone)]
pub struct Cnav2Assembler {
    sat: SatId,
    /// The last type 10 and its SOW.
    eph1: Option<(u32, Cnav2Message)>,
    /// The ephemeris pair (type 10 then 11).
    pair: Option<(Cnav2Message, Cnav2Message)>,
    clock: Option<Cnav2Message>,
    /// BDT week from the last type 10.
    week: Option<u32>,
}

impl Cnav2Assembler {
    pub fn new(sat: SatId) -> Self {
        Self {
            sat,
            eph1: None,
            pair: None,
            clock: None,
            week: None,
        }
    }

    /// BDT week of the last type 10 (the full week: 13 bits are not ambiguous).
    pub fn week(&self) -> Option<u32> {
        self.week
    }

    /// Take one message; the ephemeris when types 10, 11 and 30 of one issue are in.
    pub fn push(&mut self, msg: &Cnav2Message) -> Option<BroadcastEphemeris> {
        match msg.mes_type {
            10 => {
                self.week = Some(msg.get(&e::WN) as u32);
                self.eph1 = Some((msg.sow_s, msg.clone()));
            }
            11 => {
                let (sow, first) = self.eph1.take()?;
                if (sow + 3) % 604_800 == msg.sow_s {
                    self.pair = Some((first, msg.clone()));
                }
            }
            30 => self.clock = Some(msg.clone()),
            _ => return None,
        }
        let (first, second) = self.pair.as_ref()?;
        let clock = self.clock.as_ref()?;
        if first.get(&e::IODE) != clock.get(&e::IODC) & 0xFF {
            return None;
        }
        let mut f = Fields::default();
        for (m, fields) in [
            (first, layout::data_fields(10)),
            (second, layout::data_fields(11)),
            (clock, layout::data_fields(30)),
        ] {
            let fields = fields.unwrap_or_default();
            let values = m.fields.values_for(&fields);
            f.absorb(&fields, &values);
        }
        let week = first.get(&e::WN) as u32;
        let sow = i64::from(first.sow_s);
        let toe = e::reference_epoch(week, sow, f.get(&e::TOE) * 300);
        let toc = e::reference_epoch(week, sow, f.get(&e::TOC) * 300);
        Some(e::to_ephemeris(&f, self.sat, toe, toc, &e::TGD_B2AP))
    }
}
