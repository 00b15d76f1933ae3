//! Random choices for the generators: a seeded [`fastrand::Rng`] with the few distributions
//! the fuzz cases need, and TOML text for numbers (ordinary and extreme).

/// A seeded source of random choices. Each case has its own, derived from the run's seed,
/// the test's name and the case's index, so that any case can be replayed alone.
pub struct Gen {
    rng: fastrand::Rng,
}

/// SplitMix64's finalizer: spreads nearby seeds far apart.
pub fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Gen {
    pub fn new(seed: u64) -> Gen {
        Gen {
            rng: fastrand::Rng::with_seed(mix(seed)),
        }
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.rng.f64()
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Log-uniform in [lo, hi) (both > 0): every decade equally likely.
    pub fn log(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }

    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// Uniform in lo..=hi.
    pub fn int(&mut self, lo: u64, hi: u64) -> u64 {
        self.rng.u64(lo..=hi)
    }

    /// Uniform in 0..n (n ≥ 1).
    pub fn index(&mut self, n: usize) -> usize {
        self.rng.usize(0..n.max(1))
    }

    pub fn pick<T: Clone>(&mut self, items: &[T]) -> T {
        items[self.index(items.len())].clone()
    }

    pub fn byte(&mut self) -> u8 {
        self.rng.u8(..)
    }

    /// A random unit vector, uniform on the sphere.
    pub fn direction(&mut self) -> [f64; 3] {
        loop {
            let v = [
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            ];
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if n > 1e-3 && n <= 1.0 {
                return v.map(|c| c / n);
            }
        }
    }

    /// TOML text of a value that stresses a field: extremes of every kind, wrong types.
    pub fn extreme(&mut self) -> String {
        self.pick(&EXTREMES).to_string()
    }
}

/// Replacement values for mutations: zero and signs, the edges of f64, u32 and i64, not a
/// number, infinities, and values of the wrong TOML type.
pub const EXTREMES: [&str; 38] = [
    "0",
    "0.0",
    "-0.0",
    "1",
    "-1",
    "-1.0",
    "0.5",
    "2",
    "1e300",
    "-1e300",
    "1e-300",
    "-1e-300",
    "5e-324",
    "1.7976931348623157e308",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "1e16",
    "4294967295",
    "4294967296",
    "-4294967296",
    "9223372036854775807",
    "-9223372036854775808",
    "1000000000",
    "0.999999999999",
    "1.0000000001",
    "\"\"",
    "\"x\"",
    "\" \"",
    "\"..\"",
    "true",
    "false",
    "[]",
    "[1, 2]",
    "[nan, inf, -inf]",
    "{}",
    "1979-05-27T07:32:00Z",
];

/// TOML text of a float (TOML spells NaN and infinity `nan`, `inf`, `-inf`; Rust's `{:?}`
/// gives the shortest text that reads back to the same value, always with a `.` or an `e`).
pub fn num(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{v:?}")
    }
}

/// TOML text of a 3-vector.
pub fn vec3(v: [f64; 3]) -> String {
    format!("[{}, {}, {}]", num(v[0]), num(v[1]), num(v[2]))
}
