//! Anti-aliased data files: the layout of sub-pixel samples and the box filter every shader
//! applies to them.
//!
//! A render with `[camera] samples = s²` traces s×s rays per picture pixel on a regular
//! (stratified) grid and keeps every ray's record: the data file is an image of
//! (W·s)×(H·s) records, and picture pixel (col, row) of the W×H picture is the block of
//! records (s·col + i, s·row + j), 0 ≤ i, j < s, whose rays go through the sub-pixel
//! centres (col + (i + ½)/s, row + (j + ½)/s). The header's `godel.supersample` is s.
//!
//! Records are never averaged: g and t_emit of two hits do not average into a hit (the mean
//! of two emission times is an event neither ray saw). Shaders colour each sample and then
//! average the linear colours over the block, a box filter ([`DataFile::box_filter`]).

use crate::DataFile;

/// Largest number of samples per picture pixel along each side (256 rays per pixel).
pub const MAX_SUPERSAMPLE: u32 = 16;

impl DataFile {
    /// Samples per picture pixel along each side (s ≥ 1).
    pub fn supersample(&self) -> usize {
        self.header.supersample.max(1) as usize
    }

    /// The size of the picture (W, H): the stored image divided by the supersampling.
    pub fn picture_size(&self) -> (usize, usize) {
        let s = self.supersample();
        (self.width / s, self.height / s)
    }

    /// The indices (into `records` and the light planes) of the samples of picture pixel
    /// (`col`, `row`), row-major within the block.
    pub fn sample_indices(&self, col: usize, row: usize) -> impl Iterator<Item = usize> + '_ {
        let s = self.supersample();
        (0..s).flat_map(move |j| (0..s).map(move |i| self.index(s * col + i, s * row + j)))
    }

    /// The box filter: the mean of `colour(i)` (linear RGB of sample i) over the samples of
    /// picture pixel (`col`, `row`).
    pub fn box_filter(
        &self,
        col: usize,
        row: usize,
        colour: impl Fn(usize) -> [f32; 3],
    ) -> [f32; 3] {
        let s = self.supersample();
        if s == 1 {
            return colour(self.index(col, row));
        }
        let mut sum = [0.0f64; 3];
        for i in self.sample_indices(col, row) {
            let c = colour(i);
            for k in 0..3 {
                sum[k] += f64::from(c[k]);
            }
        }
        let n = (s * s) as f64;
        sum.map(|v| (v / n) as f32)
    }
}
