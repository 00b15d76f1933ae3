//! Where overlay text may go: rectangles on a picture, and a [`Board`] that accepts a
//! rectangle only if it lies inside the picture and keeps a gap to every rectangle accepted
//! before, so that labels, legends and reference squares never overlap or leave the picture
//! (the layout of [`crate::layer`]; a label that finds no room is left out).

/// A rectangle of pixels: columns x0..x1, rows y0..y1 (ends excluded).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rect {
    pub x0: i64,
    pub y0: i64,
    pub x1: i64,
    pub y1: i64,
}

impl Rect {
    /// The rectangle at (x, y) of size w × h.
    pub fn at(x: i64, y: i64, w: i64, h: i64) -> Rect {
        Rect {
            x0: x,
            y0: y,
            x1: x + w,
            y1: y + h,
        }
    }

    /// Whether the two rectangles come closer than `gap` pixels (overlap for gap 0).
    pub fn near(&self, other: &Rect, gap: i64) -> bool {
        self.x0 < other.x1 + gap
            && other.x0 < self.x1 + gap
            && self.y0 < other.y1 + gap
            && other.y0 < self.y1 + gap
    }

    /// Whether the rectangle lies within a `width` × `height` picture.
    pub fn inside(&self, width: i64, height: i64) -> bool {
        self.x0 >= 0 && self.y0 >= 0 && self.x1 <= width && self.y1 <= height
    }
}

/// The rectangles placed on one picture so far.
#[derive(Clone, Debug)]
pub struct Board {
    width: i64,
    height: i64,
    gap: i64,
    taken: Vec<Rect>,
}

impl Board {
    /// An empty `width` × `height` picture whose rectangles keep `gap` pixels apart.
    pub fn new(width: u32, height: u32, gap: i64) -> Board {
        Board {
            width: i64::from(width),
            height: i64::from(height),
            gap,
            taken: Vec::new(),
        }
    }

    /// Marks `r` as taken whatever lies there (something drawn in the picture itself, such
    /// as the reference squares).
    pub fn block(&mut self, r: Rect) {
        self.taken.push(r);
    }

    /// Takes `r` if it lies inside the picture and clear of everything taken; says whether.
    pub fn place(&mut self, r: Rect) -> bool {
        let free = r.inside(self.width, self.height)
            && r.x1 > r.x0
            && r.y1 > r.y0
            && !self.taken.iter().any(|t| t.near(&r, self.gap));
        if free {
            self.taken.push(r);
        }
        free
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_board_refuses_overlaps_near_misses_and_the_outside() {
        let mut b = Board::new(100, 50, 2);
        assert!(b.place(Rect::at(0, 0, 20, 10)));
        assert!(!b.place(Rect::at(10, 5, 20, 10)), "overlap");
        assert!(!b.place(Rect::at(21, 0, 10, 10)), "one pixel apart, gap 2");
        assert!(b.place(Rect::at(22, 0, 10, 10)), "two pixels apart");
        assert!(!b.place(Rect::at(95, 0, 10, 10)), "leaves the picture");
        assert!(!b.place(Rect::at(50, -1, 10, 10)), "leaves the picture");
        assert!(!b.place(Rect::at(50, 20, 0, 10)), "empty");
        b.block(Rect::at(60, 30, 10, 10));
        assert!(!b.place(Rect::at(65, 35, 5, 5)));
        assert!(b.place(Rect::at(80, 40, 20, 10)));
    }
}
