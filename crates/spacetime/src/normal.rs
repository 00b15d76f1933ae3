//! Riemann normal coordinates about an event P, to the order an object's rest frame needs
//! (e.g. Misner, Thorne & Wheeler §11.6): the displacement of a nearby event X,
//! ξ^μ = Δx^μ + ½ Γ^μ_αβ(P) Δx^α Δx^β with Δx = X − P (exact to second order), and a vector
//! carried along the short coordinate line by parallel transport to first order,
//! v ↦ v − Γ^μ_αβ Δx^α v^β (docs/physics.md, "Local objects").

use crate::vectors::Christoffel;

/// ξ = Δx + ½ Γ(Δx, Δx): the normal-coordinate displacement of the event at coordinate
/// displacement `d` from the centre where `gamma` was taken.
pub fn displacement(gamma: &Christoffel, d: [f64; 4]) -> [f64; 4] {
    Expansion::new(gamma).displacement(d)
}

/// Γ at a centre, kept for [`displacement`] from it: only its nonzero entries, in the order
/// of the full sum (Gödel's Γ has 12 of 64 at a static observer's event, 4 at the origin).
/// A product with a zero entry adds ±0 to a round-to-nearest sum that starts at +0, which
/// never changes it (such a sum never becomes −0): the result is the full sum's, bit for
/// bit, for finite displacements, at a fraction of the work.
#[derive(Clone, Debug)]
pub struct Expansion {
    /// (α, β, Γ^μ_αβ) of the nonzero entries, those of μ = 0 first, then μ = 1, …
    terms: [(usize, usize, f64); 64],
    /// terms[ends[μ − 1]..ends[μ]] are those of μ (ends[−1] = 0).
    ends: [usize; 4],
}

impl Expansion {
    pub fn new(gamma: &Christoffel) -> Expansion {
        let mut terms = [(0, 0, 0.0); 64];
        let mut ends = [0; 4];
        let mut n = 0;
        for (mu, rows) in gamma.iter().enumerate() {
            for (a, row) in rows.iter().enumerate() {
                for (b, &g) in row.iter().enumerate() {
                    if g != 0.0 {
                        terms[n] = (a, b, g);
                        n += 1;
                    }
                }
            }
            ends[mu] = n;
        }
        Expansion { terms, ends }
    }

    /// ξ = Δx + ½ Γ(Δx, Δx) for the coordinate displacement `d` from the centre.
    pub fn displacement(&self, d: [f64; 4]) -> [f64; 4] {
        let mut xi = d;
        let mut from = 0;
        for (out, &end) in xi.iter_mut().zip(&self.ends) {
            let mut c = 0.0;
            for &(a, b, g) in &self.terms[from..end] {
                // (The masks let the compiler drop the bounds checks: a, b < 4.)
                c += g * d[a & 3] * d[b & 3];
            }
            *out += 0.5 * c;
            from = end;
        }
        xi
    }
}

/// The vector `v` carried by the coordinate displacement `dx` (from its base point to the
/// destination) with parallel transport to first order: v^μ − Γ^μ_αβ dx^α v^β.
pub fn transport(gamma: &Christoffel, dx: [f64; 4], v: [f64; 4]) -> [f64; 4] {
    let mut out = v;
    for (mu, o) in out.iter_mut().enumerate() {
        for a in 0..4 {
            for b in 0..4 {
                *o -= gamma[mu][a][b] * dx[a] * v[b];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::Expansion;
    use crate::vectors::Christoffel;

    /// Numbers in [−1, 1) from a fixed seed (xorshift64*): the same cases every run.
    fn uniform(state: &mut u64) -> f64 {
        *state ^= *state >> 12;
        *state ^= *state << 25;
        *state ^= *state >> 27;
        let bits = state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        2.0 * bits as f64 / (1u64 << 53) as f64 - 1.0
    }

    /// The sparse sum is the full one bit for bit: every entry of Γ summed in order, zeros
    /// included, on Γs with many zero entries (and some −0) and displacements of all scales.
    #[test]
    fn the_sparse_expansion_is_the_full_sum_bit_for_bit() {
        let mut state = 0x9e37_79b9_7f4a_7c15;
        for case in 0..2000 {
            let mut gamma: Christoffel = [[[0.0; 4]; 4]; 4];
            for v in gamma.iter_mut().flatten().flatten() {
                let r = uniform(&mut state);
                *v = match case % 3 {
                    _ if r < -0.6 => -0.0,
                    0 if r < 0.5 => 0.0,
                    1 if r < 0.8 => 0.0,
                    _ => uniform(&mut state),
                };
            }
            let scale = 10f64.powi((case % 9) - 4);
            let d: [f64; 4] = std::array::from_fn(|_| scale * uniform(&mut state));
            let mut full = d;
            for (mu, out) in full.iter_mut().enumerate() {
                let mut c = 0.0;
                for a in 0..4 {
                    for b in 0..4 {
                        c += gamma[mu][a][b] * d[a] * d[b];
                    }
                }
                *out += 0.5 * c;
            }
            let sparse = Expansion::new(&gamma).displacement(d);
            assert_eq!(
                sparse.map(f64::to_bits),
                full.map(f64::to_bits),
                "case {case}: {sparse:?} against {full:?}"
            );
        }
    }
}
