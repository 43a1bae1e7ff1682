//! The header contract of a cutting-test CSV ([`Columns`]: which measured quantities a file
//! carries, and the located error when a command needs one it lacks) and the standard deviation of
//! repeated tests at one condition ([`derive_sd_from_repeats`]), used by
//! [`crate::tests_csv`].

use std::path::Path;

use cutcal_model::CuttingTest;

use crate::InputError;

/// A measured quantity that a command needs a column for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeasuredColumn {
    /// Cutting force Fc.
    CuttingForce,
    /// Feed (thrust) force Ft.
    FeedForce,
    /// Chip thickness tc.
    ChipThickness,
}

impl MeasuredColumn {
    /// The quantity in a message (`cutting-force column`).
    fn what(self) -> &'static str {
        match self {
            MeasuredColumn::CuttingForce => "cutting-force",
            MeasuredColumn::FeedForce => "feed-force",
            MeasuredColumn::ChipThickness => "chip-thickness",
        }
    }

    /// The column names that carry the quantity, with their units.
    fn accepted(self) -> &'static str {
        match self {
            MeasuredColumn::CuttingForce => "`fc_n_per_mm` (N/mm, per unit width) or `fc_n` (N, total over the width)",
            MeasuredColumn::FeedForce => "`ft_n_per_mm` (N/mm, per unit width) or `ft_n` (N, total over the width)",
            MeasuredColumn::ChipThickness => "`chip_mm` (mm)",
        }
    }

    fn columns(self) -> &'static [&'static str] {
        match self {
            MeasuredColumn::CuttingForce => &["fc_n_per_mm", "fc_n"],
            MeasuredColumn::FeedForce => &["ft_n_per_mm", "ft_n"],
            MeasuredColumn::ChipThickness => &["chip_mm"],
        }
    }
}

/// The header of a test CSV: its column names and the line they are on.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Columns {
    /// Column names in file order.
    pub names: Vec<String>,
    /// 1-based line of the header row.
    pub line: Option<usize>,
}

impl Columns {
    /// Whether the file has a column carrying `m`.
    #[must_use]
    pub fn has(&self, m: MeasuredColumn) -> bool {
        m.columns().iter().any(|c| self.names.iter().any(|n| n == c))
    }

    /// Checks that the file has a column for each quantity in `needs`; `purpose` says who needs
    /// them (`DPZD identification (paper Eq 15) needs Fc, Ft and tc`).
    ///
    /// Returns an error at the header line naming each missing quantity, the accepted column
    /// names and the columns found.
    pub fn require(&self, path: &Path, needs: &[MeasuredColumn], purpose: &str) -> Result<(), InputError> {
        let missing: Vec<String> = needs
            .iter()
            .filter(|m| !self.has(**m))
            .map(|m| format!("no {} column (accepted names: {})", m.what(), m.accepted()))
            .collect();
        if missing.is_empty() {
            return Ok(());
        }
        Err(InputError::new(
            path,
            self.line,
            "(header)",
            "",
            format!(
                "the file has {}; columns found: {}; {purpose}",
                missing.join(" and "),
                self.names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
            ),
        ))
    }
}

/// Sets the sample standard deviation (n - 1 denominator) of repeated tests at one condition on
/// each repeat, for the quantities `[fc, ft, chip]` marked in `which` that are not already set.
/// A condition is the tuple (speed, uncut chip thickness, width, rake, edge radius, flank wear),
/// compared to 1e-9 relative; a quantity needs two or more rows measuring it. A spread of zero
/// (identical repeats) states no uncertainty and is not set.
pub fn derive_sd_from_repeats(tests: &mut [CuttingTest], which: [bool; 3]) {
    let key = |t: &CuttingTest| {
        [
            t.speed_m_per_s,
            t.uncut_chip_thickness_m,
            t.width_m,
            t.rake_rad,
            t.edge_radius_m.unwrap_or(0.0),
            t.flank_wear_m.unwrap_or(0.0),
        ]
    };
    let same = |a: [f64; 6], b: [f64; 6]| {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1e-30))
    };
    let n = tests.len();
    let mut group = vec![usize::MAX; n];
    for i in 0..n {
        if group[i] == usize::MAX {
            group[i] = i;
            for j in i + 1..n {
                if group[j] == usize::MAX && same(key(&tests[i]), key(&tests[j])) {
                    group[j] = i;
                }
            }
        }
    }
    for (q, &wanted) in which.iter().enumerate() {
        if !wanted {
            continue;
        }
        let get = |t: &CuttingTest| match q {
            0 => t.measured.cutting_force_n_per_m,
            1 => t.measured.feed_force_n_per_m,
            _ => t.measured.chip_thickness_m,
        };
        for g in 0..n {
            let members: Vec<usize> = (0..n).filter(|&i| group[i] == g && get(&tests[i]).is_some()).collect();
            if members.len() < 2 {
                continue;
            }
            let vals: Vec<f64> = members.iter().filter_map(|&i| get(&tests[i])).collect();
            let mean = vals.iter().sum::<f64>() / vals.len() as f64;
            let sd = (vals.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (vals.len() - 1) as f64).sqrt();
            if sd.is_nan() || sd <= 0.0 {
                continue;
            }
            for &i in &members {
                let s = &mut tests[i].measured.sd;
                let slot = match q {
                    0 => &mut s.cutting_force_n_per_m,
                    1 => &mut s.feed_force_n_per_m,
                    _ => &mut s.chip_thickness_m,
                };
                if slot.is_none() {
                    *slot = Some(sd);
                }
            }
        }
    }
}
