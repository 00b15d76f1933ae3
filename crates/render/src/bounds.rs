//! Axis-aligned boxes in pseudo-Cartesian (x, y, z), used to skip whole loops of a ray that
//! come nowhere near an object (the intersection test proper is in `target.rs`).

/// A box [min, max] per axis; infinite bounds are allowed (unbounded planes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: [f64::INFINITY; 3],
        max: [f64::NEG_INFINITY; 3],
    };

    pub fn point(p: [f64; 3]) -> Aabb {
        Aabb { min: p, max: p }
    }
    pub fn add(&mut self, p: [f64; 3]) {
        for i in 0..3 {
            self.min[i] = self.min[i].min(p[i]);
            self.max[i] = self.max[i].max(p[i]);
        }
    }
    pub fn union(&mut self, o: &Aabb) {
        for i in 0..3 {
            self.min[i] = self.min[i].min(o.min[i]);
            self.max[i] = self.max[i].max(o.max[i]);
        }
    }
    /// The box grown by `m` on every side.
    pub fn grown(mut self, m: f64) -> Aabb {
        for i in 0..3 {
            self.min[i] -= m;
            self.max[i] += m;
        }
        self
    }
    /// The box moved by `dz` along z.
    pub fn shifted_z(mut self, dz: f64) -> Aabb {
        self.min[2] += dz;
        self.max[2] += dz;
        self
    }
    pub fn intersects(&self, o: &Aabb) -> bool {
        (0..3).all(|i| self.min[i] <= o.max[i] && o.min[i] <= self.max[i])
    }
    /// Largest distance of the box from the z axis (for the metric's scale there).
    pub fn max_radius(&self) -> f64 {
        let x = self.min[0].abs().max(self.max[0].abs());
        let y = self.min[1].abs().max(self.max[1].abs());
        x.hypot(y)
    }
}
