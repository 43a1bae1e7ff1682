//! Minimal deterministic SVG line and scatter plots for the reports (no fonts, no system state:
//! the same data give the same bytes on every machine).

use std::fmt::Write as _;

/// One data series.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend name.
    pub name: String,
    /// Points (x, y).
    pub points: Vec<(f64, f64)>,
    /// Draw as markers instead of a line.
    pub markers: bool,
    /// Dashed line.
    pub dashed: bool,
}

impl Series {
    /// A solid line.
    #[must_use]
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { name: name.into(), points, markers: false, dashed: false }
    }

    /// A dashed line.
    #[must_use]
    pub fn dashed(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { name: name.into(), points, markers: false, dashed: true }
    }

    /// Markers only.
    #[must_use]
    pub fn markers(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { name: name.into(), points, markers: true, dashed: false }
    }
}

/// A 2-D plot.
#[derive(Debug, Clone)]
pub struct Plot {
    /// Title.
    pub title: String,
    /// x-axis label (with unit).
    pub x_label: String,
    /// y-axis label (with unit).
    pub y_label: String,
    /// Series.
    pub series: Vec<Series>,
    /// Draw the y = x diagonal (for predicted-vs-measured plots).
    pub diagonal: bool,
}

const PALETTE: [&str; 8] = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"];
const W: f64 = 720.0;
const H: f64 = 440.0;
const L: f64 = 80.0;
const R: f64 = 190.0;
const T: f64 = 40.0;
const B: f64 = 60.0;

fn nice_step(span: f64) -> f64 {
    let raw = span / 5.0;
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let n = if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    };
    n * mag
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-12 * (1.0 + hi.abs()) {
        return (lo - 0.5 * (1.0 + lo.abs() * 0.1), hi + 0.5 * (1.0 + hi.abs() * 0.1));
    }
    let step = nice_step(hi - lo);
    ((lo / step).floor() * step, (hi / step).ceil() * step)
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

fn fmt_tick(v: f64, step: f64) -> String {
    if step >= 1.0 || v == 0.0 {
        format!("{v:.0}")
    } else {
        let d = (-step.log10().floor()) as usize;
        format!("{v:.d$}")
    }
}

impl Plot {
    /// Renders the plot as an SVG document.
    #[must_use]
    pub fn render(&self) -> String {
        let mut xs: Vec<f64> = self.series.iter().flat_map(|s| s.points.iter().map(|p| p.0)).collect();
        let mut ys: Vec<f64> = self.series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).collect();
        if self.diagonal {
            let all: Vec<f64> = xs.iter().chain(ys.iter()).copied().collect();
            xs = all.clone();
            ys = all;
        }
        let (x0, x1) = range(xs.into_iter());
        let (y0, y1) = range(ys.into_iter());
        let px = |x: f64| L + (x - x0) / (x1 - x0) * (W - L - R);
        let py = |y: f64| H - B - (y - y0) / (y1 - y0) * (H - T - B);
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" font-family="sans-serif" font-size="12">"#
        );
        let _ = writeln!(s, r#"<rect x="0" y="0" width="{W}" height="{H}" fill="white"/>"#);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="22" text-anchor="middle" font-size="15">{}</text>"#,
            (L + W - R) / 2.0,
            esc(&self.title)
        );
        let _ = writeln!(
            s,
            r#"<g id="axes" stroke="black" fill="none"><rect x="{L}" y="{T}" width="{}" height="{}"/></g>"#,
            W - L - R,
            H - T - B
        );
        let (sx, sy) = (nice_step(x1 - x0), nice_step(y1 - y0));
        let mut t = (x0 / sx).ceil() * sx;
        while t <= x1 + 1e-9 * sx {
            let _ = writeln!(
                s,
                r##"<line x1="{0:.2}" y1="{1}" x2="{0:.2}" y2="{2}" stroke="#ddd"/><text x="{0:.2}" y="{3}" text-anchor="middle">{4}</text>"##,
                px(t),
                T,
                H - B,
                H - B + 16.0,
                fmt_tick(t, sx)
            );
            t += sx;
        }
        let mut t = (y0 / sy).ceil() * sy;
        while t <= y1 + 1e-9 * sy {
            let _ = writeln!(
                s,
                r##"<line x1="{0}" y1="{1:.2}" x2="{2}" y2="{1:.2}" stroke="#ddd"/><text x="{3}" y="{4:.2}" text-anchor="end">{5}</text>"##,
                L,
                py(t),
                W - R,
                L - 6.0,
                py(t) + 4.0,
                fmt_tick(t, sy)
            );
            t += sy;
        }
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
            (L + W - R) / 2.0,
            H - 18.0,
            esc(&self.x_label)
        );
        let _ = writeln!(
            s,
            r#"<text x="18" y="{0}" text-anchor="middle" transform="rotate(-90 18 {0})">{1}</text>"#,
            (T + H - B) / 2.0,
            esc(&self.y_label)
        );
        if self.diagonal {
            let (a, b) = (x0.max(y0), x1.min(y1));
            let _ = writeln!(
                s,
                r##"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="#888" stroke-dasharray="4 4"/>"##,
                px(a),
                py(a),
                px(b),
                py(b)
            );
        }
        for (i, se) in self.series.iter().enumerate() {
            let c = PALETTE[i % PALETTE.len()];
            let _ = write!(s, r#"<g class="series" data-name="{}">"#, esc(&se.name));
            if se.markers {
                for (x, y) in se.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()) {
                    let _ = write!(s, r#"<circle cx="{:.2}" cy="{:.2}" r="4" fill="{c}"/>"#, px(*x), py(*y));
                }
            } else {
                let pts: Vec<String> = se
                    .points
                    .iter()
                    .filter(|p| p.0.is_finite() && p.1.is_finite())
                    .map(|(x, y)| format!("{:.2},{:.2}", px(*x), py(*y)))
                    .collect();
                let dash = if se.dashed { r#" stroke-dasharray="6 4""# } else { "" };
                let _ = write!(
                    s,
                    r#"<polyline fill="none" stroke="{c}" stroke-width="2"{dash} points="{}"/>"#,
                    pts.join(" ")
                );
            }
            let ly = T + 10.0 + 20.0 * i as f64;
            let lx = W - R + 12.0;
            if se.markers {
                let _ = write!(s, r#"<circle cx="{}" cy="{ly}" r="4" fill="{c}"/>"#, lx + 10.0);
            } else {
                let _ = write!(
                    s,
                    r#"<line x1="{lx}" y1="{ly}" x2="{}" y2="{ly}" stroke="{c}" stroke-width="2"{}/>"#,
                    lx + 20.0,
                    if se.dashed { r#" stroke-dasharray="6 4""# } else { "" }
                );
            }
            let _ = writeln!(s, r#"<text x="{}" y="{}">{}</text></g>"#, lx + 26.0, ly + 4.0, esc(&se.name));
        }
        s.push_str("</svg>\n");
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_every_series_and_is_deterministic() {
        let p = Plot {
            title: "t <1>".into(),
            x_label: "x [mm]".into(),
            y_label: "y [MPa]".into(),
            series: vec![Series::line("a", vec![(0.0, 1.0), (1.0, 2.0)]), Series::markers("b", vec![(0.5, 1.5)])],
            diagonal: false,
        };
        let s = p.render();
        assert_eq!(s, p.render());
        assert!(s.contains(r#"data-name="a""#) && s.contains(r#"data-name="b""#));
        assert!(s.contains("t &lt;1&gt;"));
        assert_eq!(s.matches("<g class=\"series\"").count(), 2);
    }

    #[test]
    fn nice_steps() {
        assert!((nice_step(10.0) - 2.0).abs() < 1e-12);
        assert!((nice_step(0.1) - 0.02).abs() < 1e-12);
        assert!((nice_step(700.0) - 100.0).abs() < 1e-9);
    }
}
