//! A fast 1-D table of black-body colour in the observed temperature g·T, for shaders that
//! colour millions of pixels per frame (no spectrum integral, no logarithm per pixel).
//!
//! The bin of a temperature is its f32 bit pattern shifted right by [`SHIFT`]: for positive
//! floats the bit pattern grows monotonically and almost linearly in log₂ T, so each octave
//! gets 2^(23 − SHIFT) = 1024 bins of relative width 2^-10 ≈ 0.07 % (colour changes over a bin
//! are far below one 8-bit step). Each bin holds the values of
//! [`crate::blackbody::table`] (colour at luminance 1, normalized colour, luminance Y) at the
//! bin's middle temperature. Temperatures outside [`T_MIN`], [`T_MAX`] are not in the table.

use std::sync::OnceLock;

use crate::blackbody::{normalize_max, table, T_MAX, T_MIN};

/// Bits dropped from the f32 pattern: 10 mantissa bits remain.
pub const SHIFT: u32 = 13;

/// One bin.
#[derive(Clone, Copy, Debug)]
pub struct GtEntry {
    /// Linear sRGB at luminance Y = 1.
    pub unit: [f32; 3],
    /// Linear sRGB with largest component 1.
    pub normalized: [f32; 3],
    /// Luminance Y, W·sr⁻¹·m⁻².
    pub luminance: f64,
}

/// The table.
pub struct GtTable {
    first: u32,
    entries: Vec<GtEntry>,
}

impl GtTable {
    fn new() -> GtTable {
        let first = (T_MIN as f32).to_bits() >> SHIFT;
        let last = (T_MAX as f32).to_bits() >> SHIFT;
        let tab = table();
        let entries = (first..=last)
            .map(|bin| {
                let mid = f32::from_bits((bin << SHIFT) | (1 << (SHIFT - 1)));
                let t = f64::from(mid);
                let unit = tab.unit_colour(t);
                GtEntry {
                    unit: unit.map(|c| c as f32),
                    normalized: normalize_max(unit).map(|c| c as f32),
                    luminance: tab.luminance(t),
                }
            })
            .collect();
        GtTable { first, entries }
    }

    /// The bin number (f32 bit pattern of a temperature shifted right by [`SHIFT`]) of the
    /// first entry: entry i holds bin `first_bin() + i`.
    pub fn first_bin(&self) -> u32 {
        self.first
    }

    /// The entries in bin order (the viewer uploads them to the GPU as they are).
    pub fn entries(&self) -> &[GtEntry] {
        &self.entries
    }

    /// The bin of temperature `t` (K), `None` outside the table or for non-finite `t`.
    pub fn get(&self, t: f64) -> Option<&GtEntry> {
        if !(T_MIN..=T_MAX).contains(&t) {
            return None;
        }
        let bin = (t as f32).to_bits() >> SHIFT;
        self.entries.get(bin.checked_sub(self.first)? as usize)
    }
}

/// The shared table, built on first use.
pub fn gt_table() -> &'static GtTable {
    static TABLE: OnceLock<GtTable> = OnceLock::new();
    TABLE.get_or_init(GtTable::new)
}
