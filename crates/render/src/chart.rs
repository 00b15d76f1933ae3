//! The coordinates in which local objects are described (docs/physics.md, "Local objects"
//! and "The Gödel-type family"): a ball's rest-frame coordinates are Riemann normal
//! coordinates to second order, which depend on the chart they are expanded in at third
//! order in the ball's size. Gödel's and Minkowski's balls are expanded in the metric's own
//! coordinates; a Gödel-type member's in its Gödel-like chart (`spacetime::GodelChart`), so
//! that the Gödel member's balls are exactly Gödel's.

use spacetime::{
    Christoffel, Event, FourVector, GodelChart, Metric, MetricTensor, Spacetime, Tetrad,
};

/// The chart of local descriptions for one metric.
#[derive(Clone, Copy, Debug)]
pub enum LocalChart {
    /// The metric's own coordinates.
    Own(Metric),
    /// A Gödel-type member's Gödel-like chart.
    GodelLike(GodelChart),
}

impl LocalChart {
    pub fn of(metric: &Metric) -> LocalChart {
        match metric.godel_type() {
            Some(member) => LocalChart::GodelLike(GodelChart::new(member)),
            None => LocalChart::Own(*metric),
        }
    }

    /// The event `e` (metric's coordinates) in this chart.
    pub fn event(&self, e: Event) -> Event {
        match self {
            LocalChart::Own(_) => e,
            LocalChart::GodelLike(c) => c.event(e),
        }
    }

    /// The vector `v` at `at` (metric's coordinates) in this chart.
    pub fn vector(&self, at: Event, v: FourVector) -> FourVector {
        match self {
            LocalChart::Own(_) => v,
            LocalChart::GodelLike(c) => c.vector(at, v),
        }
    }

    /// A vector of this chart at the event `at` (metric's coordinates) back in the metric's
    /// coordinates.
    pub fn vector_back(&self, at: Event, v: FourVector) -> FourVector {
        match self {
            LocalChart::Own(_) => v,
            LocalChart::GodelLike(c) => c.vector_back(at, v),
        }
    }

    /// The frame `f` at `at` (metric's coordinates) in this chart.
    pub fn frame(&self, at: Event, f: &Tetrad) -> Tetrad {
        Tetrad {
            e: f.e.map(|e| self.vector(at, e)),
        }
    }

    /// g_μν at `x`, an event of this chart.
    pub fn metric(&self, x: Event) -> MetricTensor {
        match self {
            LocalChart::Own(m) => m.metric(x),
            LocalChart::GodelLike(c) => c.metric(x),
        }
    }

    /// Γ at `x`, an event of this chart.
    pub fn christoffel(&self, x: Event) -> Christoffel {
        match self {
            LocalChart::Own(m) => m.christoffel(x),
            LocalChart::GodelLike(c) => c.christoffel(x),
        }
    }
}
