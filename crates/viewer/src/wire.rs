//! The binary format in which the server hands arrays to the page's WebGL2 code: a data
//! file's channels, texture images, the black-body table. One small fixed header, then the
//! samples, little-endian, so that the page wraps the bytes in a typed array and uploads
//! them as a texture without converting anything.
//!
//! | bytes | content |
//! | --- | --- |
//! | 0..4 | magic `GDL1` |
//! | 4..8 | width (u32) |
//! | 8..12 | height (u32) |
//! | 12 | sample type: 1 u8, 2 u16, 3 u32, 4 f32 |
//! | 13 | components per sample (1..=4) |
//! | 14..16 | zero |
//! | 16.. | width × height × components samples, row-major, row 0 first |
//!
//! The header is 16 bytes, so the samples of every type start aligned for a typed array.
//!
//! A **sequence** of arrays (several channels in one answer, [`sequence`]) is the arrays one
//! after another, each padded with zeros to a multiple of 4 bytes, so that every array's
//! samples start aligned as well; each array's header gives its length.

/// First four bytes of every array.
pub const MAGIC: [u8; 4] = *b"GDL1";
/// Length of the header in bytes.
pub const HEADER_LEN: usize = 16;

/// How the samples are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SampleType {
    U8 = 1,
    U16 = 2,
    U32 = 3,
    F32 = 4,
}

impl SampleType {
    /// Bytes per sample.
    pub fn size(self) -> usize {
        match self {
            SampleType::U8 => 1,
            SampleType::U16 => 2,
            SampleType::U32 | SampleType::F32 => 4,
        }
    }
}

/// An array being written: the header first, then samples pushed in order.
pub struct Array {
    bytes: Vec<u8>,
}

impl Array {
    /// Starts an array of `width` × `height` samples of `components` values of type `kind`.
    pub fn new(width: usize, height: usize, kind: SampleType, components: u8) -> Array {
        let len = width * height * usize::from(components) * kind.size();
        let mut bytes = Vec::with_capacity(HEADER_LEN + len);
        bytes.extend_from_slice(&MAGIC);
        bytes.extend_from_slice(&(width as u32).to_le_bytes());
        bytes.extend_from_slice(&(height as u32).to_le_bytes());
        bytes.extend_from_slice(&[kind as u8, components, 0, 0]);
        Array { bytes }
    }

    pub fn push_u8(&mut self, x: u8) {
        self.bytes.push(x);
    }

    pub fn push_u16(&mut self, x: u16) {
        self.bytes.extend_from_slice(&x.to_le_bytes());
    }

    pub fn push_u32(&mut self, x: u32) {
        self.bytes.extend_from_slice(&x.to_le_bytes());
    }

    pub fn push_f32(&mut self, x: f32) {
        self.bytes.extend_from_slice(&x.to_le_bytes());
    }

    /// The finished bytes.
    pub fn finish(self) -> Vec<u8> {
        self.bytes
    }
}

/// The arrays one after another, each padded with zeros to a multiple of 4 bytes.
pub fn sequence(arrays: impl IntoIterator<Item = Vec<u8>>) -> Vec<u8> {
    let mut out = Vec::new();
    for a in arrays {
        out.extend_from_slice(&a);
        out.resize(out.len().next_multiple_of(4), 0);
    }
    out
}

/// The arrays of a [`sequence`], each without its padding; `None` for anything that is not
/// one (for tests and tools that read arrays back).
pub fn split_sequence(mut bytes: &[u8]) -> Option<Vec<&[u8]>> {
    let mut out = Vec::new();
    while !bytes.is_empty() {
        let (w, h, kind, components) = read_header(bytes)?;
        let len = w
            .checked_mul(h)?
            .checked_mul(usize::from(components) * kind.size())?
            .checked_add(HEADER_LEN)?;
        let padded = len.checked_next_multiple_of(4)?;
        out.push(bytes.get(..len)?);
        bytes = bytes.get(padded..)?;
    }
    Some(out)
}

/// A parsed header: (width, height, sample type, components), for tests and tools that read
/// arrays back; `None` for anything that is not one.
pub fn read_header(bytes: &[u8]) -> Option<(usize, usize, SampleType, u8)> {
    let h = bytes.get(..HEADER_LEN)?;
    if h[..4] != MAGIC {
        return None;
    }
    let word = |i: usize| u32::from_le_bytes([h[i], h[i + 1], h[i + 2], h[i + 3]]) as usize;
    let kind = match h[12] {
        1 => SampleType::U8,
        2 => SampleType::U16,
        3 => SampleType::U32,
        4 => SampleType::F32,
        _ => return None,
    };
    Some((word(4), word(8), kind, h[13]))
}
