//! Tables of the shadow's outputs against one knob, interpolated by monotone piecewise-cubic
//! Hermite splines (Fritsch & Carlson, SIAM J. Numer. Anal. 17 (1980) 238-246): C1, no overshoot
//! between nodes, exact at the nodes.

use crate::error::DiagnoseError;

/// Outputs per node: `ln Fc, ln Ft, ln t2, T_AB, T_int`.
pub const WIDTH: usize = 5;

/// One knob's table at one test, restricted to the contiguous run of solved nodes around the off
/// value; outside that run the value is held at the end node (the knob has no further effect).
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    u: Vec<f64>,
    y: Vec<[f64; WIDTH]>,
    slope: Vec<[f64; WIDTH]>,
    off: f64,
    at_off: [f64; WIDTH],
}

impl Table {
    /// Builds the table from ascending `nodes` and their values (`None`: the model had no solution
    /// there); `off` must be a node with a value.
    ///
    /// Returns an error if `off` is not a solved node.
    pub fn new(nodes: &[f64], values: &[Option<[f64; WIDTH]>], off: f64) -> Result<Self, DiagnoseError> {
        let k0 = nodes
            .iter()
            .position(|u| (u - off).abs() <= 1e-12 * off.abs().max(1.0))
            .filter(|&k| values[k].is_some())
            .ok_or_else(|| DiagnoseError::Inconsistent(format!("table: no solved node at the off value {off}")))?;
        let mut lo = k0;
        while lo > 0 && values[lo - 1].is_some() {
            lo -= 1;
        }
        let mut hi = k0;
        while hi + 1 < nodes.len() && values[hi + 1].is_some() {
            hi += 1;
        }
        let u: Vec<f64> = nodes[lo..=hi].to_vec();
        let y: Vec<[f64; WIDTH]> = values[lo..=hi].iter().map(|v| v.unwrap_or([0.0; WIDTH])).collect();
        let slope = fritsch_carlson(&u, &y);
        let mut t = Self { u, y, slope, off, at_off: [0.0; WIDTH] };
        t.at_off = t.at(off);
        Ok(t)
    }

    /// Interpolated outputs at `v` (held at the end nodes outside the table).
    #[must_use]
    pub fn at(&self, v: f64) -> [f64; WIDTH] {
        let n = self.u.len();
        if n == 1 || v <= self.u[0] {
            return self.y[0];
        }
        if v >= self.u[n - 1] {
            return self.y[n - 1];
        }
        let k = self.u.partition_point(|x| *x <= v).saturating_sub(1).min(n - 2);
        let h = self.u[k + 1] - self.u[k];
        let s = (v - self.u[k]) / h;
        let (h00, h10, h01, h11) = (
            2.0 * s.powi(3) - 3.0 * s * s + 1.0,
            s.powi(3) - 2.0 * s * s + s,
            -2.0 * s.powi(3) + 3.0 * s * s,
            s.powi(3) - s * s,
        );
        let mut out = [0.0; WIDTH];
        for (j, o) in out.iter_mut().enumerate() {
            *o = h00 * self.y[k][j]
                + h10 * h * self.slope[k][j]
                + h01 * self.y[k + 1][j]
                + h11 * h * self.slope[k + 1][j];
        }
        out
    }

    /// `at(off)`, kept from construction.
    #[must_use]
    pub fn at_off(&self) -> [f64; WIDTH] {
        self.at_off
    }

    /// `at(v) - at(off)`; exactly zero at the off value itself, without interpolating.
    #[must_use]
    pub fn delta(&self, v: f64) -> [f64; WIDTH] {
        if v.to_bits() == self.off.to_bits() {
            return [0.0; WIDTH];
        }
        let a = self.at(v);
        let mut d = [0.0; WIDTH];
        for j in 0..WIDTH {
            d[j] = a[j] - self.at_off[j];
        }
        d
    }

    /// The solved range of the knob.
    #[must_use]
    pub fn range(&self) -> (f64, f64) {
        (self.u[0], self.u[self.u.len() - 1])
    }
}

/// Node slopes of the monotone cubic interpolant (Fritsch & Carlson 1980, steps 1-5).
fn fritsch_carlson(u: &[f64], y: &[[f64; WIDTH]]) -> Vec<[f64; WIDTH]> {
    let n = u.len();
    let mut m = vec![[0.0; WIDTH]; n];
    if n < 2 {
        return m;
    }
    for j in 0..WIDTH {
        let d: Vec<f64> = (0..n - 1).map(|k| (y[k + 1][j] - y[k][j]) / (u[k + 1] - u[k])).collect();
        m[0][j] = d[0];
        m[n - 1][j] = d[n - 2];
        for k in 1..n - 1 {
            m[k][j] = if d[k - 1] * d[k] <= 0.0 { 0.0 } else { 0.5 * (d[k - 1] + d[k]) };
        }
        for k in 0..n - 1 {
            if d[k] == 0.0 {
                m[k][j] = 0.0;
                m[k + 1][j] = 0.0;
                continue;
            }
            let (a, b) = (m[k][j] / d[k], m[k + 1][j] / d[k]);
            let r = a * a + b * b;
            if r > 9.0 {
                let t = 3.0 / r.sqrt();
                m[k][j] = t * a * d[k];
                m[k + 1][j] = t * b * d[k];
            }
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    fn col(f: impl Fn(f64) -> f64, u: &[f64]) -> Vec<Option<[f64; WIDTH]>> {
        u.iter().map(|&x| Some([f(x), 2.0 * f(x), 0.0, 0.0, 0.0])).collect()
    }

    #[test]
    fn exact_at_nodes_and_for_lines_and_close_for_smooth_curves() {
        let u: Vec<f64> = (0..9).map(|i| f64::from(i) * 0.25).collect();
        let t = Table::new(&u, &col(|x| 3.0 * x - 1.0, &u), 0.0).unwrap();
        for x in [0.0, 0.1, 0.37, 1.0, 1.99] {
            assert!((t.at(x)[0] - (3.0 * x - 1.0)).abs() < 1e-12);
        }
        let t = Table::new(&u, &col(f64::exp, &u), 0.0).unwrap();
        for &x in &u {
            assert!((t.at(x)[1] - 2.0 * x.exp()).abs() < 1e-12);
        }
        // Cubic Hermite with 0.25 spacing: e^x within 1e-2 relative in between.
        for x in [0.13, 0.88, 1.61] {
            assert!((t.at(x)[0] / x.exp() - 1.0).abs() < 1e-2, "{x}");
        }
        assert_eq!(t.delta(0.0), [0.0; WIDTH]);
    }

    #[test]
    fn unsolved_nodes_cut_the_table_and_values_are_held_beyond() {
        let u = [0.0, 1.0, 2.0, 3.0, 4.0];
        let mut v = col(|x| x * x, &u);
        v[3] = None;
        let t = Table::new(&u, &v, 1.0).unwrap();
        assert_eq!(t.range(), (0.0, 2.0));
        assert_eq!(t.at(3.5)[0], 4.0);
        assert!(Table::new(&u, &v, 3.0).is_err());
    }

    #[test]
    fn monotone_data_give_a_monotone_interpolant() {
        // A step-like sequence: a plain cubic spline overshoots; Fritsch-Carlson must not.
        let u = [0.0, 1.0, 2.0, 3.0, 4.0];
        let v: Vec<Option<[f64; WIDTH]>> = [0.0, 0.0, 1.0, 1.0, 1.0].iter().map(|&y| Some([y; WIDTH])).collect();
        let t = Table::new(&u, &v, 0.0).unwrap();
        let mut last = -1.0;
        for i in 0..=400 {
            let y = t.at(f64::from(i) / 100.0)[0];
            assert!(y >= last - 1e-15 && (-1e-15..=1.0 + 1e-15).contains(&y));
            last = y;
        }
    }
}
