//! Published Johnson-Cook sets per material class, and the plausibility box for n, C and m that
//! they span.
//!
//! The joint Oxley identification ([`crate::joint`]) fits five parameters to a handful of forces.
//! Without a physical box it returns sets no metallurgist would accept (issue 15: A 267 MPa,
//! B 1155 MPa, n 0.60, C 0.003, m 0.70 for AISI 1045). The box used here is the envelope of the
//! published sets of the material's class, widened by a stated margin: n and m by 20 % of the
//! extreme value on each side, C by a factor 1.5 (published C values scatter on a log scale). It is
//! a plausibility box, not a law: a set outside it is reported as such, never hidden.
//!
//! Sources of the sets (A and B in MPa, eps0 = 1/s unless stated):
//! - Johnson & Cook 1983, Proc. 7th Int. Symp. Ballistics, The Hague, pp. 541-547, Table 1
//!   (Armco iron, 1006 steel, 4340 steel, S-7 tool steel, 2024-T351 and 7039 aluminium);
//! - Jaspers & Dautzenberg 2002, J. Mater. Process. Technol. 122:322-330, Table 3 (AISI 1045,
//!   AA6082-T6);
//! - Lee & Lin 1998, J. Mater. Process. Technol. 75:127-136 (Ti6Al4V);
//! - Meyer & Kleponis 2001, Int. J. Impact Eng. 26:509-521 (Ti6Al4V);
//! - Kay 2003, DOT/FAA/AR-03/57 (Ti6Al4V);
//! - Seo, Min & Yang 2005, Int. J. Impact Eng. 31:735-754 (Ti6Al4V, SHPB at high temperature);
//! - Lesuer, Kay & LeBlanc 2001, LLNL UCRL-JC-134118 (AA6061-T6);
//! - Brar, Joshi & Harris 2009, Proc. 11th Hypervelocity Impact Symp. (AA7075-T651);
//! - the paper (Table 5: C38, 42CrMo4, AA6082).

use serde::Serialize;

/// A material class with a literature box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MaterialClass {
    /// Ferrous metals: carbon, alloy and tool steels, iron.
    Steel,
    /// Titanium alloys.
    Titanium,
    /// Aluminium alloys.
    Aluminium,
}

impl MaterialClass {
    /// Every class.
    pub const ALL: [MaterialClass; 3] = [MaterialClass::Steel, MaterialClass::Titanium, MaterialClass::Aluminium];

    /// The class's name as written in reports and on the command line.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            MaterialClass::Steel => "steel",
            MaterialClass::Titanium => "titanium",
            MaterialClass::Aluminium => "aluminium",
        }
    }

    /// Parses a class name (`steel`, `titanium`, `aluminium` or `aluminum`).
    #[must_use]
    pub fn parse(s: &str) -> Option<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "steel" => Some(MaterialClass::Steel),
            "titanium" => Some(MaterialClass::Titanium),
            "aluminium" | "aluminum" => Some(MaterialClass::Aluminium),
            _ => None,
        }
    }

    /// The class of a metal from its room-temperature density, kg/m^3: aluminium alloys 2500-3000,
    /// titanium alloys 4300-4800, steels 7600-8100 (handbook ranges, e.g. ASM Handbook Vol. 2 and 1).
    /// Other densities have no class (`None`): the caller then keeps the user's bounds and says so.
    #[must_use]
    pub fn from_density(density_kg_per_m3: f64) -> Option<Self> {
        match density_kg_per_m3 {
            d if (2500.0..=3000.0).contains(&d) => Some(MaterialClass::Aluminium),
            d if (4300.0..=4800.0).contains(&d) => Some(MaterialClass::Titanium),
            d if (7600.0..=8100.0).contains(&d) => Some(MaterialClass::Steel),
            _ => None,
        }
    }
}

/// One published JC set.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PublishedSet {
    /// Material designation.
    pub material: &'static str,
    /// Its class.
    pub class: MaterialClass,
    /// A, MPa.
    pub a_mpa: f64,
    /// B, MPa.
    pub b_mpa: f64,
    /// Strain-hardening exponent n.
    pub n: f64,
    /// Strain-rate constant C.
    pub c: f64,
    /// Thermal-softening exponent m.
    pub m: f64,
    /// Where it was published.
    pub source: &'static str,
}

const fn set(
    material: &'static str,
    class: MaterialClass,
    [a_mpa, b_mpa, n, c, m]: [f64; 5],
    source: &'static str,
) -> PublishedSet {
    PublishedSet { material, class, a_mpa, b_mpa, n, c, m, source }
}

use MaterialClass::{Aluminium, Steel, Titanium};

/// The published sets the boxes are built from (module documentation gives the full references).
pub const PUBLISHED_SETS: [PublishedSet; 16] = [
    set("1006 steel", Steel, [350.0, 275.0, 0.36, 0.022, 1.00], "Johnson & Cook 1983"),
    set("4340 steel", Steel, [792.0, 510.0, 0.26, 0.014, 1.03], "Johnson & Cook 1983"),
    set("S-7 tool steel", Steel, [1539.0, 477.0, 0.18, 0.012, 1.00], "Johnson & Cook 1983"),
    set("AISI 1045", Steel, [553.1, 600.8, 0.234, 0.0134, 1.0], "Jaspers & Dautzenberg 2002"),
    set("Armco iron", Steel, [175.0, 380.0, 0.32, 0.060, 0.55], "Johnson & Cook 1983"),
    set("C38", Steel, [589.0, 145.0, 0.25, 0.069, 1.1], "the paper, Table 5"),
    set("42CrMo4", Steel, [530.0, 153.0, 0.25, 0.117, 1.1], "the paper, Table 5"),
    set("Ti6Al4V", Titanium, [782.7, 498.4, 0.28, 0.028, 1.0], "Lee & Lin 1998"),
    set("Ti6Al4V", Titanium, [862.0, 331.0, 0.34, 0.012, 0.8], "Meyer & Kleponis 2001"),
    set("Ti6Al4V", Titanium, [1098.0, 1092.0, 0.93, 0.014, 1.1], "Kay 2003"),
    set("Ti6Al4V", Titanium, [997.9, 653.1, 0.45, 0.0198, 0.7], "Seo et al. 2005"),
    set("2024-T351", Aluminium, [265.0, 426.0, 0.34, 0.015, 1.00], "Johnson & Cook 1983"),
    set("7039", Aluminium, [337.0, 343.0, 0.41, 0.010, 1.00], "Johnson & Cook 1983"),
    set("AA6082-T6", Aluminium, [428.5, 327.7, 1.008, 0.00747, 1.31], "Jaspers & Dautzenberg 2002"),
    set("AA6061-T6", Aluminium, [324.0, 114.0, 0.42, 0.002, 1.34], "Lesuer et al. 2001"),
    set("AA7075-T651", Aluminium, [546.0, 678.0, 0.71, 0.024, 1.56], "Brar et al. 2009"),
];

/// Relative margin on n and m beyond the published extremes.
pub const MARGIN_N_M: f64 = 0.2;
/// Factor on C beyond the published extremes (C scatters on a log scale).
pub const FACTOR_C: f64 = 1.5;

/// The plausibility box of one class for n, C and m.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LiteratureBox {
    /// The class.
    pub class: MaterialClass,
    /// n range.
    pub n: [f64; 2],
    /// C range.
    pub c: [f64; 2],
    /// m range.
    pub m: [f64; 2],
    /// The sets it spans, as "material (source)".
    pub sets: Vec<String>,
}

impl LiteratureBox {
    /// The envelope of the class's published sets widened by [`MARGIN_N_M`] and [`FACTOR_C`].
    #[must_use]
    pub fn of(class: MaterialClass) -> Self {
        let sets: Vec<&PublishedSet> = PUBLISHED_SETS.iter().filter(|s| s.class == class).collect();
        let range = |f: &dyn Fn(&PublishedSet) -> f64| {
            sets.iter().fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], s| [lo.min(f(s)), hi.max(f(s))])
        };
        let [n_lo, n_hi] = range(&|s| s.n);
        let [c_lo, c_hi] = range(&|s| s.c);
        let [m_lo, m_hi] = range(&|s| s.m);
        Self {
            class,
            n: [n_lo * (1.0 - MARGIN_N_M), n_hi * (1.0 + MARGIN_N_M)],
            c: [c_lo / FACTOR_C, c_hi * FACTOR_C],
            m: [m_lo * (1.0 - MARGIN_N_M), m_hi * (1.0 + MARGIN_N_M)],
            sets: sets.iter().map(|s| format!("{} ({})", s.material, s.source)).collect(),
        }
    }

    /// The parameters of a set that lie outside the box, each as "name value outside [lo, hi]".
    #[must_use]
    pub fn outside(&self, n: f64, c: f64, m: f64) -> Vec<String> {
        [("n", n, self.n), ("C", c, self.c), ("m", m, self.m)]
            .iter()
            .filter(|(_, v, [lo, hi])| v < lo || v > hi)
            .map(|(name, v, [lo, hi])| format!("{name} {v:.4} outside [{lo:.4}, {hi:.4}]"))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_published_set_lies_inside_its_own_class_box() {
        for s in &PUBLISHED_SETS {
            let b = LiteratureBox::of(s.class);
            assert!(b.outside(s.n, s.c, s.m).is_empty(), "{} ({})", s.material, s.source);
        }
    }

    #[test]
    fn the_steel_box_is_the_widened_envelope_of_the_steel_sets() {
        // Ferrous extremes by hand from the table: n 0.18 (S-7) .. 0.36 (1006), C 0.012 (S-7) ..
        // 0.117 (42CrMo4), m 0.55 (Armco iron) .. 1.1 (C38, 42CrMo4).
        let b = LiteratureBox::of(MaterialClass::Steel);
        for (got, want) in [
            (b.n[0], 0.18 * 0.8),
            (b.n[1], 0.36 * 1.2),
            (b.c[0], 0.012 / 1.5),
            (b.c[1], 0.117 * 1.5),
            (b.m[0], 0.55 * 0.8),
            (b.m[1], 1.1 * 1.2),
        ] {
            assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        }
        assert_eq!(b.sets.len(), 7);
        // The non-physical AISI 1045 set (n 0.60, C 0.003, m 0.70): n and C are outside.
        assert_eq!(
            b.outside(0.60, 0.003, 0.70),
            vec!["n 0.6000 outside [0.1440, 0.4320]".to_string(), "C 0.0030 outside [0.0080, 0.1755]".to_string()]
        );
    }

    #[test]
    fn classes_from_density() {
        assert_eq!(MaterialClass::from_density(7862.0), Some(MaterialClass::Steel));
        assert_eq!(MaterialClass::from_density(4430.0), Some(MaterialClass::Titanium));
        assert_eq!(MaterialClass::from_density(2700.0), Some(MaterialClass::Aluminium));
        assert_eq!(MaterialClass::from_density(8960.0), None);
        assert_eq!(MaterialClass::parse("Aluminum"), Some(MaterialClass::Aluminium));
    }
}
