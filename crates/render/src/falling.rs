//! Rejection of balls in free fall, loop by loop of a ray (docs/physics.md, "Balls in free
//! fall").
//!
//! A free-falling centre moves through the static observers' space at the constant speed
//! √(γ² − 1) per unit of its proper time (γ = −u_t is conserved), and its coordinate time
//! changes by at most U = γ + √2·√(γ² − 1) per unit of proper time (u^t = γ + g_ti u^i and
//! |g_ti u^i| ≤ √2 times the static length of u's spatial part). So the worldline, cut into
//! cells of proper time Δτ, lies within static distance m = √(γ² − 1)·Δτ/2 of each cell's
//! middle point, at coordinate times within U·Δτ/2 of its time. A point X inside the
//! renderer's ball (|ξ| ≤ R at the simultaneous centre) lies within static distance 1.08·R
//! of the centre's point Q that the static observer at X counts as simultaneous (X − Q
//! orthogonal to ∂t: static observers see the ball contracted, never larger; measured
//! ≤ 1.0000·R) and within coordinate time 1.08·√2·R of Q (coordinate time differs from
//! static time by g_ti Δx^i, at most √2 times the static length; measured ≤ 0.89·√2·R).
//! A loop of a ray (origin frame: t monotone along it, from kΔ to (k+1)Δ) can therefore
//! meet the ball only at ray points within static distance M = reach + m of some cell whose
//! time lies within the loop's window widened by S = 1.08·√2·R + U·Δτ/2; the ray's circle
//! (`crate::circle`) and its linear z give the first and the last λ of the loop where that
//! may happen. Before the loops, one disc holding every cell (centre C, hyperbolic radius r):
//! a ray whose circle passes farther than M + r from C all round passes farther than M from
//! every cell, and no loop searches.
//!
//! Cells span R/2 of proper time and are tested three at a time, as a block: every point
//! within M of a cell's middle lies within M + r_b of the block's point (r_b: its farthest
//! cell's distance), so a block's λ window holds its cells'. A loop's first λ is then found
//! from the blocks in the order of their windows' first λ, each searched cell by cell until
//! the next block's window starts at or after the first λ found; the last λ likewise. That is
//! the first and the last λ of all the cells, for the angles of a few cells more than cells
//! of R alone would take, with M and S smaller by the half cell (docs/physics.md, "Balls in
//! free fall", "Blocks of cells").

use crate::circle::RayCircle;
use crate::target::Target;
use crate::worldline::Worldline;
use spacetime::isometry::disc;
use spacetime::{Complex, Event, Isometry, Metric};
use std::f64::consts::SQRT_2;

/// A ball point lies within REACH_PER_RADIUS·R (static distance) of the centre's point that
/// the static observer there counts as simultaneous, and within that times √2 in coordinate
/// time (checked by the property test `a_falling_ball_lies_within_its_reach`, which asserts a
/// ratio of 1.05; the worst found were 1.0000 in space and 0.89 in time, up to 0.95 c, centres
/// out to 3a). Every λ window grows with it, so it is no wider than that needs.
pub const REACH_PER_RADIUS: f64 = 1.08;

/// Added to the reach and to the time slack, per a: the numeric tracer's deviation from the
/// closed form (as `crate::reject::REACH_PER_A`).
pub const SLACK_PER_A: f64 = 1e-6;

/// At most this many cells per worldline (longer worldlines get longer cells).
const MAX_CELLS: f64 = 4096.0;

/// A stretch of the worldline, in the origin frame of the rays' start.
#[derive(Clone, Copy, Debug)]
struct Cell {
    /// Coordinate time, disc coordinate, 1 − |w|² and height of the middle point.
    t: f64,
    w: Complex,
    nw: f64,
    z: f64,
}

impl Cell {
    /// The cell as [`FallingBall::window`] tests it, within the distance whose cosh is
    /// `cosh_m` of its point.
    fn region(&self, cosh_m: f64) -> Region {
        Region {
            w: self.w,
            nw: self.nw,
            cosh_m,
            z: (self.z, self.z),
            t: (self.t, self.t),
        }
    }
}

/// What a loop's window is found for ([`FallingBall::window`]): the ray within the distance
/// whose cosh is `cosh_m` of the disc point w (`nw` = 1 − |w|²), at a height within M of
/// [z.0, z.1] and a time within S of [t.0, t.1]. A cell's, or a block's.
#[derive(Clone, Copy, Debug)]
struct Region {
    w: Complex,
    nw: f64,
    cosh_m: f64,
    z: (f64, f64),
    t: (f64, f64),
}

/// Consecutive cells of the worldline, tested as one before their cells are: every point
/// within M of a cell's middle lies within M + r of the block's point w (r: the largest
/// distance from w to its cells' middles), at a height within M of the cells' heights, and
/// a cell's band of times lies within the block's.
#[derive(Clone, Copy, Debug)]
struct Block {
    /// The middle cell's point, within M + r; its cells' least and greatest height and time.
    region: Region,
    /// r.
    radius: f64,
    /// Its cells: `cells[first..end]`.
    first: usize,
    end: usize,
}

/// A block whose window of a loop may hold the loop's first or last λ near the ball, with
/// that window.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    block: usize,
    from: f64,
    until: f64,
}

/// A ball in free fall, seen from the origin frame of the rays' start.
#[derive(Clone, Debug)]
pub struct FallingBall {
    a: f64,
    /// In the order of proper time.
    cells: Vec<Cell>,
    /// Sorted by their least time.
    blocks: Vec<Block>,
    /// The longest span of times a block's cells cover.
    block_span: f64,
    /// Static distance M = reach + m within which a ray point may be in the ball, and
    /// cosh(M/a).
    near: f64,
    cosh_near: f64,
    /// Time slack S between a ray point and the cells that may hold its centre.
    slack: f64,
    /// The least and the greatest height of the cells, and of their times.
    z_range: (f64, f64),
    t_range: (f64, f64),
    /// A disc holding every cell's point: its centre C, 1 − |C|² and its hyperbolic radius r.
    disc: (Complex, f64, f64),
    /// cosh((M + r)/a): a ray's circle farther than M + r from C all round meets no cell.
    cosh_beyond: f64,
}

impl FallingBall {
    /// The ball of `target` seen from the origin frame of `from` (a pixel ray's observer or
    /// a light: times of rays count from `from.t`), if it is a local ball in free fall in
    /// Gödel's universe with parameter `a` (None otherwise).
    pub fn new(a: f64, metric: &Metric, from: Event, target: &Target) -> Option<FallingBall> {
        let Target::LocalSphere {
            radius,
            worldline: w @ Worldline::Free(_),
        } = target
        else {
            return None;
        };
        let (tau_min, tau_max, gamma) = w.free_fall_range()?;
        let speed = (gamma * gamma - 1.0).max(0.0).sqrt(); // γv
        let span = tau_max - tau_min;
        let dtau = (CELL_PER_RADIUS * radius).max(span / MAX_CELLS);
        let n = ((span / dtau).ceil() as usize).max(1);
        let to = Isometry::to_origin(a, from);
        let mut cells = Vec::with_capacity(n);
        for i in 0..n {
            let tau = (tau_min + (i as f64 + 0.5) * dtau).min(tau_max);
            let p = to.apply(w.at(metric, tau)?.event);
            let wd = disc(a, p.x, p.y);
            cells.push(Cell {
                t: p.t,
                w: wd,
                nw: 1.0 - wd.norm_sqr(),
                z: p.z,
            });
        }
        if !cells.iter().all(|c| c.t.is_finite() && c.nw > 0.0) {
            return None;
        }
        let (z_range, t_range) = (extent(&cells, |c| c.z), extent(&cells, |c| c.t));
        let reach = REACH_PER_RADIUS * radius + SLACK_PER_A * a;
        let near = reach + 0.5 * speed * dtau;
        let u_t = gamma + SQRT_2 * speed;
        // The disc's centre: the cells' mean point (any point of the disc would do).
        let c = cells.iter().fold(Complex::new(0.0, 0.0), |s, p| s + p.w);
        let c = c.scale(1.0 / cells.len() as f64);
        let nc = 1.0 - c.norm_sqr();
        let r = farthest(a, (c, nc), &cells);
        if !(nc > 0.0 && r.is_finite()) {
            return None;
        }
        let mut blocks: Vec<Block> = cells
            .chunks(CELLS_PER_BLOCK)
            .enumerate()
            .map(|(j, chunk)| {
                let mid = chunk[chunk.len() / 2];
                let radius = farthest(a, (mid.w, mid.nw), chunk);
                let first = j * CELLS_PER_BLOCK;
                Block {
                    region: Region {
                        w: mid.w,
                        nw: mid.nw,
                        cosh_m: ((near + radius) / a).cosh(),
                        z: extent(chunk, |c| c.z),
                        t: extent(chunk, |c| c.t),
                    },
                    radius,
                    first,
                    end: first + chunk.len(),
                }
            })
            .collect();
        if !blocks.iter().all(|b| b.radius.is_finite()) {
            return None;
        }
        blocks.sort_by(|p, q| p.region.t.0.total_cmp(&q.region.t.0));
        let block_span = blocks
            .iter()
            .map(|b| b.region.t.1 - b.region.t.0)
            .fold(0.0, f64::max);
        Some(FallingBall {
            a,
            cells,
            blocks,
            block_span,
            near,
            cosh_near: (near / a).cosh(),
            slack: REACH_PER_RADIUS * SQRT_2 * radius + 0.5 * u_t * dtau + SLACK_PER_A * a,
            z_range,
            t_range,
            disc: (c, nc, r),
            cosh_beyond: ((near + r) / a).cosh(),
        })
    }

    /// The same test with its reach and time slack scaled by `factor`: a test that compares
    /// records with and without the rejection uses factor < 1 (an over-eager bound) to see
    /// that the comparison catches it.
    pub fn scaled(mut self, factor: f64) -> FallingBall {
        self.near *= factor;
        self.cosh_near = (self.near / self.a).cosh();
        self.cosh_beyond = ((self.near + self.disc.2) / self.a).cosh();
        for b in &mut self.blocks {
            b.region.cosh_m = ((self.near + b.radius) / self.a).cosh();
        }
        self.slack *= factor;
        self
    }

    /// For the ray `ray` starting at time `t_start` (relative to `from.t`), per loop k
    /// (λ ∈ [k·λ_ret, (k+1)·λ_ret]) while k·λ_ret < `until`: the stretch of the loop, λ
    /// counted from its start, that must search the ball, pushed to `out` (cleared first):
    /// from the first λ where the ray may be within the ball (from the loop's start where
    /// `whole_start`) up to the last. Loops past the end of `out` need no search. False when
    /// unsure (then `out` means nothing and every loop searches the ball).
    pub fn loops(
        &self,
        ray: &RayCircle,
        t_start: f64,
        until: f64,
        whole_start: bool,
        out: &mut Vec<LoopWindow>,
    ) -> bool {
        out.clear();
        let (first, last) = (self.t_range.0 - self.slack, self.t_range.1 + self.slack);
        let dt = ray.dt_loop;
        if !(dt != 0.0 && dt.is_finite() && ray.l_ret > 0.0 && t_start.is_finite()) {
            return false;
        }
        // Farther than M from every cell all round the circle: no loop searches.
        let (c, nc, _) = self.disc;
        if ray.beyond(c, nc, self.cosh_beyond) {
            return true;
        }
        // The λ where the ray's height p_z λ is within M of some cell's (widened far beyond
        // rounding): every cell's λ window in `near_in` lies inside it.
        let (z_lo, z_hi) = (self.z_range.0 - self.near, self.z_range.1 + self.near);
        let (heights_from, heights_until) = if ray.pz == 0.0 {
            if z_lo <= 0.0 && 0.0 <= z_hi {
                (f64::NEG_INFINITY, f64::INFINITY)
            } else {
                (f64::INFINITY, f64::NEG_INFINITY)
            }
        } else {
            let (p, q) = (z_lo / ray.pz, z_hi / ray.pz);
            let margin = 1e-9 * (p.abs().max(q.abs()) + ray.l_ret);
            (p.min(q) - margin, p.max(q) + margin)
        };
        let mut needed = 0;
        // The ray's times over its first loop, made for the first cell near its circle (most
        // rays have none) and shifted to every other loop.
        let mut times: Option<LoopTimes> = None;
        for k in 0..=scene::MAX_RAY_LOOPS {
            let kf = k as f64;
            let l0 = kf * ray.l_ret;
            let (ta, tb) = (t_start + kf * dt, t_start + (kf + 1.0) * dt);
            // Loops beyond the worldline's times, in the ray's direction, or beyond its
            // heights (λ only leads farther from them) need nothing.
            if l0 >= until
                || (dt < 0.0 && ta < first)
                || (dt > 0.0 && ta > last)
                || l0 > heights_until
            {
                out.truncate(needed);
                return true;
            }
            let l1 = (l0 + ray.l_ret).min(until);
            let near = if l1 < heights_from {
                None // not yet within the heights
            } else {
                self.near_in(
                    ray,
                    (ta.min(tb), ta.max(tb), t_start),
                    (kf, l0, l1),
                    &mut times,
                )
            };
            out.push(near.map_or(LoopWindow::NONE, |(f, u)| LoopWindow {
                from: if whole_start { 0.0 } else { f - l0 },
                until: u - l0,
            }));
            if near.is_some() {
                needed = out.len();
            }
        }
        false
    }

    /// The first and the last λ in [l0, l1] (loop k, with times in [t_lo, t_hi] and
    /// `t_start` at λ = 0) at which the ray may be within the ball; `times` is the ray's
    /// table of times, made here when first needed. Each block's window holds its cells'
    /// (module documentation), so only the blocks whose windows reach below the first λ
    /// found so far, or beyond the last, are searched cell by cell, from the outermost in.
    fn near_in(
        &self,
        ray: &RayCircle,
        band: (f64, f64, f64),
        stretch: (f64, f64, f64),
        times: &mut Option<LoopTimes>,
    ) -> Option<(f64, f64)> {
        self.near_in_at_most(ray, band, stretch, times, MAX_CANDIDATES)
    }

    /// [`FallingBall::near_in`], with at most `max` blocks (and at most [`MAX_CANDIDATES`])
    /// searched cell by cell: with more, the blocks' own first and last λ.
    fn near_in_at_most(
        &self,
        ray: &RayCircle,
        (t_lo, t_hi, t_start): (f64, f64, f64),
        (k, l0, l1): (f64, f64, f64),
        times: &mut Option<LoopTimes>,
        max: usize,
    ) -> Option<(f64, f64)> {
        let (band_lo, band_hi) = (t_lo - self.slack, t_hi + self.slack);
        let i0 = self
            .blocks
            .partition_point(|b| b.region.t.0 < band_lo - self.block_span);
        let loop_ = Loop::new(ray, self.near, (k, l0, l1), t_start);
        let mut candidates = [Candidate {
            block: 0,
            from: 0.0,
            until: 0.0,
        }; MAX_CANDIDATES];
        let (mut n, mut hull, mut overflow): (usize, Option<(f64, f64)>, bool) = (0, None, false);
        for (j, b) in self.blocks[i0..].iter().enumerate() {
            if b.region.t.0 > band_hi {
                break;
            }
            if b.region.t.1 < band_lo {
                continue;
            }
            let Some((from, until)) = self.window(ray, &loop_, &b.region, None, times) else {
                continue;
            };
            hull = Some(widened(hull, (from, until)));
            if n == max.min(MAX_CANDIDATES) {
                overflow = true;
                continue;
            }
            candidates[n] = Candidate {
                block: i0 + j,
                from,
                until,
            };
            n += 1;
        }
        if overflow {
            return hull; // too many to search cell by cell: the blocks' own
        }
        let candidates = &mut candidates[..n];
        let mut near: Option<(f64, f64)> = None;
        // A block's cells, each unless its stretch could not widen `near` at the end
        // `lower` (or the other).
        let mut refine = |block: usize, lower: bool, near: &mut Option<(f64, f64)>| {
            let b = &self.blocks[block];
            for cell in &self.cells[b.first..b.end] {
                if cell.t < band_lo || cell.t > band_hi {
                    continue;
                }
                let inside = near.map(|(f, u)| {
                    if lower {
                        (f, f64::INFINITY)
                    } else {
                        (f64::NEG_INFINITY, u)
                    }
                });
                let region = cell.region(self.cosh_near);
                if let Some((f, u)) = self.window(ray, &loop_, &region, inside, times) {
                    *near = Some(widened(*near, (f, u)));
                }
            }
        };
        // The first λ: blocks by their windows' first λ, until one starts at or after it.
        candidates.sort_unstable_by(|p, q| p.from.total_cmp(&q.from));
        for c in candidates.iter() {
            if near.is_some_and(|(f, _)| c.from >= f) {
                break;
            }
            refine(c.block, true, &mut near);
        }
        // The last λ likewise, from the latest end.
        candidates.sort_unstable_by(|p, q| q.until.total_cmp(&p.until));
        for c in candidates.iter() {
            if near.is_some_and(|(_, u)| c.until <= u) {
                break;
            }
            refine(c.block, false, &mut near);
        }
        near
    }

    /// The first and the last λ of the loop `l` at which the ray may lie in `region`; None
    /// if nowhere, or if the stretch would lie within `inside` (it could not widen it).
    fn window(
        &self,
        ray: &RayCircle,
        l: &Loop,
        region: &Region,
        inside: Option<(f64, f64)>,
        times: &mut Option<LoopTimes>,
    ) -> Option<(f64, f64)> {
        let Region {
            w,
            nw,
            cosh_m,
            z: (z0, z1),
            t: (t0, t1),
        } = *region;
        let m = self.near;
        if z1 < l.z_lo || z0 > l.z_hi {
            return None;
        }
        // The λ window where p_z λ is within M of [z0, z1].
        let (lo, hi) = if ray.pz == 0.0 {
            if z0 > m || z1 < -m {
                return None;
            }
            (l.l0, l.l1)
        } else {
            let (p, q) = ((z0 - m) / ray.pz, (z1 + m) / ray.pz);
            (p.min(q).max(l.l0), p.max(q).min(l.l1))
        };
        let within = |lo: f64, hi: f64| inside.is_some_and(|(f, u)| f <= lo && hi <= u);
        if lo > hi || lo.is_nan() || hi.is_nan() || within(lo, hi) {
            return None;
        }
        let passing = ray.passes(w, nw, cosh_m)?;
        // Within that, where the ray's time is within S of [t0, t1] (worth its table of
        // times only where the band of times leaves out much of the loop's).
        let (lo, hi) = if ray.dt_loop.abs() > TIME_GATE * self.slack {
            let times = times.get_or_insert_with(|| LoopTimes::new(ray, l.t_start));
            let (ta, tb) = times.within(l.k, t0 - self.slack, t1 + self.slack)?;
            let (lo, hi) = (lo.max(ta), hi.min(tb));
            if lo > hi || within(lo, hi) {
                return None;
            }
            (lo, hi)
        } else {
            (lo, hi)
        };
        let arc = ray.arc_of(passing, cosh_m)?;
        Some((arc.first_in(lo, hi)?, arc.last_in(lo, hi)?))
    }
}

/// The farthest of `cells`' points from the disc point c (`nc` = 1 − |c|²), in hyperbolic
/// distance, cosh(d/a) = 1 + 2|w − c|²/((1 − |w|²)(1 − |c|²)); widened far above rounding.
fn farthest(a: f64, (c, nc): (Complex, f64), cells: &[Cell]) -> f64 {
    let r = cells
        .iter()
        .map(|p| a * (1.0 + 2.0 * (p.w - c).norm_sqr() / (nc * p.nw)).acosh())
        .fold(0.0, f64::max);
    r * (1.0 + 1e-9) + 1e-9 * a
}

/// The least and the greatest of `of` over `cells`.
fn extent(cells: &[Cell], of: fn(&Cell) -> f64) -> (f64, f64) {
    cells
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
            (lo.min(of(c)), hi.max(of(c)))
        })
}

/// The least stretch [first λ, last λ] holding `so_far` (if any) and [f, u].
fn widened(so_far: Option<(f64, f64)>, (f, u): (f64, f64)) -> (f64, f64) {
    so_far.map_or((f, u), |(f0, u0)| (f0.min(f), u0.max(u)))
}

/// One loop of a ray, for [`FallingBall::window`]: its number k, its λ range [l0, l1], the
/// heights it reaches widened by M (and a margin far above rounding), and the time at λ = 0.
struct Loop {
    k: f64,
    l0: f64,
    l1: f64,
    z_lo: f64,
    z_hi: f64,
    t_start: f64,
}

impl Loop {
    fn new(ray: &RayCircle, m: f64, (k, l0, l1): (f64, f64, f64), t_start: f64) -> Loop {
        let (z0, z1) = (ray.pz * l0, ray.pz * l1);
        let margin = 1e-9 * (z0.abs().max(z1.abs()) + m);
        Loop {
            k,
            l0,
            l1,
            z_lo: z0.min(z1) - m - margin,
            z_hi: z0.max(z1) + m + margin,
            t_start,
        }
    }
}

/// The proper time a cell spans, in radii of the ball (R and R/4 alone, or R/4 in blocks of
/// eight, measured slower on the reference scene; module documentation).
const CELL_PER_RADIUS: f64 = 0.5;

/// Cells a block holds (four: more angles).
const CELLS_PER_BLOCK: usize = 3;

/// Blocks of one loop searched cell by cell at most; beyond, the loop takes the blocks' own
/// window (wider, still holding every cell's).
const MAX_CANDIDATES: usize = 16;

/// A ray's time table is made where a loop's time spans more than TIME_GATE·S.
const TIME_GATE: f64 = 4.0;

/// Nodes of a ray's time table ([`LoopTimes`]), besides its start.
const TIME_NODES: usize = 4;

/// The ray's coordinate time (origin frame of the ball's test) at equally spaced λ of its first
/// loop, with the sign that makes it increase: where it lies within a band of times is bounded
/// from the nodes and the largest rate |dt/dλ| ≤ |E| ([`spacetime::OriginGeodesic::time`]).
/// Loop k repeats the first shifted by k·λ_ret in λ and k·Δt in time (`RayCircle::dt_loop`),
/// so one table serves them all.
struct LoopTimes {
    step: f64,
    l_ret: f64,
    dt_loop: f64,
    /// sgn(Δt)·t at the nodes (non-decreasing).
    u: [f64; TIME_NODES + 1],
    sign: f64,
    rate: f64,
    /// Added to each end of a λ window: far above rounding.
    margin: f64,
}

impl LoopTimes {
    #[inline(never)]
    fn new(ray: &RayCircle, t_start: f64) -> LoopTimes {
        let step = ray.l_ret / TIME_NODES as f64;
        let sign = if ray.dt_loop < 0.0 { -1.0 } else { 1.0 };
        LoopTimes {
            step,
            l_ret: ray.l_ret,
            dt_loop: ray.dt_loop,
            u: std::array::from_fn(|j| sign * (t_start + ray.geo.time(j as f64 * step))),
            sign,
            rate: ray.geo.energy.abs() * (1.0 + 1e-9),
            margin: 1e-9 * ray.l_ret,
        }
    }

    /// A λ window of loop n holding every λ where the ray's time lies in [t_lo, t_hi]
    /// (None: nowhere; the whole loop when unsure).
    fn within(&self, n: f64, t_lo: f64, t_hi: f64) -> Option<(f64, f64)> {
        // The band moved to the first loop's times.
        let (t_lo, t_hi) = (t_lo - n * self.dt_loop, t_hi - n * self.dt_loop);
        let (u1, u2) = if self.sign > 0.0 {
            (t_lo, t_hi)
        } else {
            (-t_hi, -t_lo)
        };
        let (first, last) = (self.u[0], self.u[TIME_NODES]);
        let l0 = n * self.l_ret;
        let l = |j: usize| l0 + j as f64 * self.step;
        if !(first.is_finite() && last.is_finite() && self.rate > 0.0) {
            return Some((l(0), l(TIME_NODES)));
        }
        if last < u1 || first > u2 {
            return None;
        }
        // Entering: the last node before the band, from which t rises at most at the rate.
        let j = self.u.partition_point(|&u| u < u1);
        let from = if j == 0 {
            l(0)
        } else {
            l(j).min(l(j - 1) + (u1 - self.u[j - 1]) / self.rate)
        };
        // Leaving: the first node past the band, which t reached at most at the rate.
        let k = self.u.partition_point(|&u| u <= u2);
        let until = if k > TIME_NODES {
            l(TIME_NODES)
        } else {
            l(k - 1).max(l(k) - (self.u[k] - u2) / self.rate)
        };
        let margin = self.margin * (1.0 + n);
        Some((from - margin, until + margin))
    }
}

/// The stretch of one loop of a ray, λ counted from the loop's start, that searches a ball
/// in free fall ([`FallingBall::loops`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopWindow {
    pub from: f64,
    pub until: f64,
}

impl LoopWindow {
    /// No search in this loop.
    pub const NONE: LoopWindow = LoopWindow {
        from: f64::INFINITY,
        until: f64::NEG_INFINITY,
    };
    /// The whole loop and on (a loop that does not close).
    pub const ALL: LoopWindow = LoopWindow {
        from: f64::NEG_INFINITY,
        until: f64::INFINITY,
    };

    /// Whether the stretch [l0, l1] (from the loop's start) meets the window.
    pub fn meets(&self, l0: f64, l1: f64) -> bool {
        l0 <= self.until && l1 >= self.from
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scene::Motion;
    use spacetime::{
        photon_tangent, ExactGeodesic, Godel, LocalVelocity, Spacetime, TimeDirection,
    };

    /// Blocks searched from the window's ends give the first and the last λ of every cell,
    /// as a loop over all the cells does, on rays past balls falling at up to 0.8 c; and the
    /// blocks' own windows are wider in many loops (the search by cells is not vacuous). With
    /// fewer blocks allowed than a loop needs searched, the window is the blocks' own, which
    /// holds the cells'.
    #[test]
    fn blocks_give_the_first_and_last_lambda_of_all_their_cells() {
        let mut random = testkit::Uniform::new(0x9e37_79b9_7f4a_7c15u64);
        let mut uniform = || random.draw();
        let a = 1.0;
        let metric = Metric::Godel(Godel::new(a));
        let (mut loops, mut found, mut wider, mut capped) = (0, 0, 0, 0);
        for _ in 0..12 {
            let start = Event::new(
                0.0,
                2.0 * uniform() - 1.0,
                2.0 * uniform() - 1.0,
                0.2 * uniform() - 0.1,
            );
            let dir = [uniform() - 0.5, uniform() - 0.5, 0.2 * uniform() - 0.1];
            let motion = Motion::Geodesic {
                start,
                velocity: LocalVelocity::new(0.8 * uniform(), dir).expect("a velocity"),
            };
            let radius = 0.15 + 0.3 * uniform();
            let target = Target::LocalSphere {
                radius,
                worldline: Worldline::new(metric, &motion, -30.0, 2.0).expect("a worldline"),
            };
            let obs = Event::new(0.0, 0.0, 0.0, 0.0);
            let ball = FallingBall::new(a, &metric, obs, &target).expect("a falling ball");
            for _ in 0..300 {
                let n = [uniform() - 0.5, uniform() - 0.5, 0.3 * (uniform() - 0.5)];
                let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                let n = n.map(|c| c / len);
                let k = photon_tangent(&metric.static_frame(obs), n, TimeDirection::Past);
                let geo = ExactGeodesic::new(a, obs, k).expect("a light ray");
                let ray = RayCircle::new(&geo.origin);
                let mut times = None;
                for k in 0..8 {
                    let kf = k as f64;
                    let (l0, l1) = (kf * ray.l_ret, (kf + 1.0) * ray.l_ret);
                    let (ta, tb) = (kf * ray.dt_loop, (kf + 1.0) * ray.dt_loop);
                    let band = (ta.min(tb), ta.max(tb), 0.0);
                    let got = ball.near_in(&ray, band, (kf, l0, l1), &mut times);
                    let one = ball.near_in_at_most(&ray, band, (kf, l0, l1), &mut times, 1);
                    // Every cell, one by one; and every block, by its own window.
                    let (lo, hi) = (band.0 - ball.slack, band.1 + ball.slack);
                    let l = Loop::new(&ray, ball.near, (kf, l0, l1), 0.0);
                    let hull = |acc: Option<(f64, f64)>, w: Option<(f64, f64)>| {
                        w.map(|w| widened(acc, w)).or(acc)
                    };
                    let by_cells = ball
                        .cells
                        .iter()
                        .filter(|c| c.t >= lo && c.t <= hi)
                        .map(|c| {
                            let region = c.region(ball.cosh_near);
                            ball.window(&ray, &l, &region, None, &mut times)
                        })
                        .fold(None, hull);
                    let by_blocks = ball
                        .blocks
                        .iter()
                        .filter(|b| b.region.t.1 >= lo && b.region.t.0 <= hi)
                        .map(|b| ball.window(&ray, &l, &b.region, None, &mut times))
                        .fold(None, hull);
                    loops += 1;
                    match (got, by_cells) {
                        (None, None) => {}
                        (Some((f, u)), Some((f0, u0))) => {
                            let tol = 1e-9 * ray.l_ret;
                            assert!(
                                (f - f0).abs() <= tol && (u - u0).abs() <= tol,
                                "loop {k}: [{f}, {u}] against the cells' [{f0}, {u0}]"
                            );
                            found += 1;
                            let (fb, ub) = by_blocks.expect("the blocks hold the cells");
                            if fb < f0 - 1e-3 * ray.l_ret || ub > u0 + 1e-3 * ray.l_ret {
                                wider += 1;
                            }
                            // One block searched cell by cell at most: where more than one
                            // would be, the blocks' own window, which holds the cells'.
                            let (f1, u1) = one.expect("a window");
                            assert!(f1 <= f0 + tol && u1 >= u0 - tol, "loop {k}: one block");
                            if (f1, u1) == (fb, ub) && (f1, u1) != (f, u) {
                                capped += 1;
                            }
                        }
                        (got, cells) => panic!("loop {k}: {got:?} against the cells' {cells:?}"),
                    }
                }
            }
        }
        assert!(found * 20 >= loops, "{found} of {loops} loops near a ball");
        assert!(
            wider * 4 >= found,
            "the blocks' own windows wider in {wider} of {found}"
        );
        assert!(
            capped * 10 >= found,
            "one block at most: {capped} of {found}"
        );
    }
}
