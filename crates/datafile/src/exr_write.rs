//! Writing an OpenEXR image into memory, the one way this workspace writes them: a single
//! scan-line layer in increasing line order, so that the (parallel) writer emits its blocks
//! in a fixed order and the same image always gives the same bytes. Used by the data file
//! (`codec.rs`) and by the linear pictures of the `shade` crate.

use std::io::Cursor;

use exr::prelude::{
    AnyChannel, AnyChannels, Blocks, Compression, Encoding, FlatSamples, Image, Layer,
    LayerAttributes, LineOrder, WritableImage,
};

/// The most an encoding reserves for its bytes in advance (256 MiB).
const MAX_RESERVE: usize = 1 << 28;

/// The bytes of a single-layer, scan-line OpenEXR image of `size` (width, height) holding
/// `channels` (stored sorted by name, as OpenEXR requires) and `attributes`, compressed with
/// `compression`; on failure the exr crate's error as text.
pub fn exr_bytes(
    size: (usize, usize),
    attributes: LayerAttributes,
    compression: Compression,
    channels: Vec<AnyChannel<FlatSamples>>,
) -> Result<Vec<u8>, String> {
    // Room for the samples uncompressed (4 bytes each at most) and the header, so that the
    // writer does not copy what it wrote into ever larger buffers (pages are touched only as
    // written); at most MAX_RESERVE, beyond which the buffer grows as it needs.
    let raw = 4 * size.0 * size.1 * channels.len() + (1 << 16);
    let capacity = raw.min(MAX_RESERVE);
    let encoding = Encoding {
        compression,
        blocks: Blocks::ScanLines,
        line_order: LineOrder::Increasing,
    };
    let layer = Layer::new(
        size,
        attributes,
        encoding,
        AnyChannels::sort(channels.into()),
    );
    let mut bytes = Vec::with_capacity(capacity);
    Image::from_layer(layer)
        .write()
        .to_buffered(Cursor::new(&mut bytes))
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}
