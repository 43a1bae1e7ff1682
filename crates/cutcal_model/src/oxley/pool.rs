//! The points a one-dimensional root search in phi has seen, and the next iterate from them:
//! inverse quadratic interpolation through the three points of smallest residual, else the secant
//! through the two best (the interpolation steps of Brent 1973, Ch. 4, without its bracket).

/// Points `(x, f(x))` of one root search, at most [`Pool::CAP`]; the worst is dropped when full.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pool {
    pts: [(f64, f64); Pool::CAP],
    n: usize,
}

impl Pool {
    pub const CAP: usize = 8;

    pub fn new() -> Self {
        Self { pts: [(f64::NAN, f64::NAN); Self::CAP], n: 0 }
    }

    /// Adds a point (non-finite values and repeated abscissae are ignored).
    pub fn push(&mut self, x: f64, fx: f64) {
        if !(x.is_finite() && fx.is_finite()) || self.pts[..self.n].iter().any(|p| p.0.to_bits() == x.to_bits()) {
            return;
        }
        if self.n < Self::CAP {
            self.pts[self.n] = (x, fx);
            self.n += 1;
        } else if let Some((i, _)) = self.pts.iter().enumerate().max_by(|a, b| a.1 .1.abs().total_cmp(&b.1 .1.abs())) {
            if fx.abs() < self.pts[i].1.abs() {
                self.pts[i] = (x, fx);
            }
        }
    }

    pub fn len(&self) -> usize {
        self.n
    }

    /// The three points of smallest |f|, best first (one insertion pass; ties keep the earlier
    /// point, as a stable sort would). Unused slots are NaN.
    fn sorted(&self) -> [(f64, f64); 3] {
        let mut s = [(f64::NAN, f64::NAN); 3];
        let mut k = 0;
        for &p in &self.pts[..self.n] {
            let mut i = k.min(2);
            if k == 3 && !(p.1.abs() < s[2].1.abs()) {
                continue;
            }
            while i > 0 && p.1.abs() < s[i - 1].1.abs() {
                s[i] = s[i - 1];
                i -= 1;
            }
            s[i] = p;
            k = (k + 1).min(3);
        }
        s
    }

    /// Whether a point within `width` of `x` has f of the opposite sign to `fx` (a certified
    /// bracket of a root, by continuity).
    pub fn brackets(&self, x: f64, fx: f64, width: f64) -> bool {
        self.pts[..self.n].iter().any(|&(xi, fi)| (xi - x).abs() <= width && (fi > 0.0) != (fx > 0.0))
    }

    /// The point with the smallest |f|.
    pub fn best(&self) -> Option<(f64, f64)> {
        (self.n > 0).then(|| self.sorted()[0])
    }

    /// The next iterate: inverse quadratic interpolation `x(f = 0)` through the three best points
    /// when it stays within `max_step` of the best point and inside the span of the points widened
    /// by `max_step`, else the secant through the two best, limited to `max_step`. `None` with fewer
    /// than two points or a flat secant.
    pub fn next(&self, max_step: f64) -> Option<f64> {
        if self.n < 2 {
            return None;
        }
        let s = self.sorted();
        let (x0, f0) = s[0];
        if self.n >= 3 {
            let ((x1, f1), (x2, f2)) = (s[1], s[2]);
            if f0 - f1 != 0.0 && f0 - f2 != 0.0 && f1 - f2 != 0.0 {
                // Lagrange interpolation of x as a function of f, at f = 0.
                let x = x0 * f1 * f2 / ((f0 - f1) * (f0 - f2))
                    + x1 * f0 * f2 / ((f1 - f0) * (f1 - f2))
                    + x2 * f0 * f1 / ((f2 - f0) * (f2 - f1));
                let (lo, hi) = (x0.min(x1).min(x2) - max_step, x0.max(x1).max(x2) + max_step);
                if x.is_finite() && (x - x0).abs() <= max_step && x >= lo && x <= hi {
                    return Some(x);
                }
            }
        }
        let (x1, f1) = s[1];
        let slope = (f1 - f0) / (x1 - x0);
        if !(slope.is_finite() && slope != 0.0) {
            return None;
        }
        Some(x0 - (f0 / slope).clamp(-max_step, max_step))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iterates_converge_to_a_cubic_root() {
        // f(x) = x^3 - 2x - 5, root 2.0945514815423265 (Wallis's example).
        let f = |x: f64| x * x * x - 2.0 * x - 5.0;
        let mut pool = Pool::new();
        for x in [2.0, 2.2] {
            pool.push(x, f(x));
        }
        for _ in 0..10 {
            let x = pool.next(0.5).unwrap();
            pool.push(x, f(x));
        }
        assert!((pool.best().unwrap().0 - 2.094_551_481_542_326_5).abs() < 1e-12);
    }

    #[test]
    fn top_three_match_a_full_sort() {
        // A deterministic scramble of |f| values with ties; the selection must agree with a stable
        // sort by |f| (the order the pool used before the one-pass selection).
        for seed in 0..50u64 {
            let mut pool = Pool::new();
            let mut all = Vec::new();
            for i in 0..Pool::CAP as u64 {
                let v = ((seed * 7 + i * 13) % 11) as f64 - 5.0;
                pool.push(i as f64, v);
                all.push((i as f64, v));
            }
            all.sort_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
            let top = pool.sorted();
            for k in 0..3 {
                assert_eq!(top[k].0.to_bits(), all[k].0.to_bits(), "seed {seed}, rank {k}");
            }
        }
    }

    #[test]
    fn keeps_the_best_points_when_full() {
        let mut pool = Pool::new();
        for i in 0..20 {
            pool.push(i as f64, 20.0 - i as f64);
        }
        assert_eq!(pool.len(), Pool::CAP);
        assert_eq!(pool.best().unwrap().0.to_bits(), 19f64.to_bits());
    }
}
