//! Raw OpenEXR header handling for the data file: a plausibility check of the
//! pixel size before decoding, and the canonical (sorted) attribute order that
//! makes encoded files byte-identical.

use std::io::Cursor;

use super::DataFileErrorKind;

/// Checks the header before exr decodes pixels: one flat layer, and a pixel
/// size that the file could plausibly hold, so that a damaged size field
/// cannot make the decoder allocate gigabytes. ZIP (deflate) expands data at
/// most about 1032-fold; 4096 leaves room for the other compressions.
pub(super) fn check_layout(bytes: &[u8]) -> Result<(), DataFileErrorKind> {
    let meta = exr::meta::MetaData::read_from_buffered(Cursor::new(bytes), true)
        .map_err(|e| DataFileErrorKind::Exr(e.to_string()))?;
    let [header] = meta.headers.as_slice() else {
        return Err(DataFileErrorKind::Layout(format!(
            "{} layers, expected exactly one",
            meta.headers.len()
        )));
    };
    if header.deep {
        return Err(DataFileErrorKind::Layout("deep data".into()));
    }
    let (width, height) = (header.layer_size.x(), header.layer_size.y());
    let decoded = width
        .checked_mul(height)
        .and_then(|pixels| pixels.checked_mul(header.channels.bytes_per_pixel.max(1)));
    let budget = bytes.len().saturating_mul(4096).saturating_add(1 << 20);
    match decoded {
        Some(size) if size <= budget => Ok(()),
        _ => Err(DataFileErrorKind::Layout(format!(
            "{width}×{height} pixels of {} bytes cannot come from a {}-byte file",
            header.channels.bytes_per_pixel,
            bytes.len()
        ))),
    }
}

/// Sorts the attributes of a single-part EXR header by name, in place.
///
/// Header layout: magic (4 bytes), version (4), then attributes
/// `name\0 type\0 size:i32 value[size]`, ended by a single `\0`. Reordering
/// keeps the header's length, so the offset table stays valid.
pub(super) fn sort_header_attributes(bytes: &mut [u8]) -> Result<(), String> {
    let malformed = || "encoder produced an unexpected header".to_string();
    let flags = bytes.get(4..8).ok_or_else(malformed)?;
    if flags[1] & 0x10 != 0 {
        return Err("encoder produced a multi-part file".into()); // not from us
    }
    let start = 8;
    let mut pos = start;
    let mut attributes: Vec<(usize, usize, usize)> = Vec::new(); // start, name end, end
    while *bytes.get(pos).ok_or_else(malformed)? != 0 {
        let nul = |from: usize| {
            bytes
                .get(from..)?
                .iter()
                .position(|&b| b == 0)
                .map(|n| from + n)
        };
        let name_end = nul(pos).ok_or_else(malformed)?;
        let type_end = nul(name_end + 1).ok_or_else(malformed)?;
        let size = bytes
            .get(type_end + 1..type_end + 5)
            .ok_or_else(malformed)?;
        let size = i32::from_le_bytes([size[0], size[1], size[2], size[3]]);
        let size = usize::try_from(size).map_err(|_| malformed())?;
        let end = type_end + 5 + size;
        if end > bytes.len() {
            return Err(malformed());
        }
        attributes.push((pos, name_end, end));
        pos = end;
    }
    attributes.sort_by(|a, b| bytes[a.0..a.1].cmp(&bytes[b.0..b.1]));
    let sorted: Vec<u8> = attributes
        .iter()
        .flat_map(|a| bytes[a.0..a.2].iter().copied())
        .collect();
    bytes[start..pos].copy_from_slice(&sorted);
    Ok(())
}
