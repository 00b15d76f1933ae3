//! Flat spacetime, ds² = −dt² + dx² + dy² + dz²: the reference against which the
//! tracer's Gödel-independent machinery (cameras, intersection, aberration) is tested.

use crate::metric::Spacetime;
use crate::vectors::MetricTensor;
use crate::vectors::{Covector, Event, FourVector, Tetrad};

#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Minkowski;

const ETA: MetricTensor = [
    [-1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

impl Spacetime for Minkowski {
    fn metric(&self, _x: Event) -> MetricTensor {
        ETA
    }
    fn inverse_metric(&self, _x: Event) -> MetricTensor {
        ETA
    }
    fn metric_derivatives(&self, _x: Event) -> [MetricTensor; 4] {
        [[[0.0; 4]; 4]; 4]
    }
    fn hamilton(&self, _x: Event, p: Covector) -> (FourVector, Covector) {
        (FourVector::new(-p.t, p.x, p.y, p.z), Covector::default())
    }
    fn static_frame(&self, _x: Event) -> Tetrad {
        Tetrad {
            e: [
                FourVector::new(1.0, 0.0, 0.0, 0.0),
                FourVector::new(0.0, 1.0, 0.0, 0.0),
                FourVector::new(0.0, 0.0, 1.0, 0.0),
                FourVector::new(0.0, 0.0, 0.0, 1.0),
            ],
        }
    }
}
