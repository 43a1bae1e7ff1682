//! Scores of one generator family from the outcomes: false positives on nulls with the 95 % Wilson
//! interval, naming per mechanism (at ENR >= 2 with its n, and over every ENR), the confusion matrix,
//! decoy abstention and the held-out RMS change. Every figure is over every dataset of its kind; a
//! dataset whose generation failed or whose diagnosis returned an error is counted and shown.

use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use super::mechanism::{DECOYS, MECHANISMS};

mod breakdown;
use breakdown::{binned, by_rival, by_shadow_fidelity, misses_by_cause};

/// What the detector said about one dataset (only the report keys the benchmark reads).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Outcome {
    /// `a`, `b` or `c`.
    pub family: String,
    /// Index within the family.
    pub index: usize,
    /// Hidden kind.
    pub hidden: String,
    /// ENR, when generated.
    pub enr: Option<f64>,
    /// Shape ENR (each output's mean shift removed), when generated.
    pub enr_shape: Option<f64>,
    /// ENR beyond the stated nuisance (`detectable.rs`), when generated and available.
    #[serde(default)]
    pub enr_beyond_nuisance: Option<f64>,
    /// The sum of squares the nuisance and the nearest rival in the generator's own form leave of
    /// the noise-free effect (`detectable::nearest_rival`), when generated and available.
    #[serde(default)]
    pub rival_chi2: Option<f64>,
    /// That rival.
    #[serde(default)]
    pub nearest_rival: Option<String>,
    /// `ok`, `generation_failed` or `diagnosis_error` (`generated` under `--generate-only`).
    pub status: String,
    /// The error, when not ok.
    pub reason: String,
    /// `verdict`.
    pub verdict: Option<String>,
    /// `selected`.
    pub selected: Vec<String>,
    /// `ambiguous_with`.
    pub ambiguous_with: Vec<String>,
    /// `fit.before.loco.all`, %.
    pub loco_before: Option<f64>,
    /// `fit.after.loco.all`, %.
    pub loco_after: Option<f64>,
    /// `shadow_rms_pct`: the fitted shadow's RMS against the simulation, %.
    #[serde(default)]
    pub shadow_rms_pct: Option<f64>,
    /// Wall time of the diagnosis, s.
    pub seconds: f64,
}

impl Outcome {
    fn ok(&self) -> bool {
        self.status == "ok"
    }
    fn claims(&self) -> bool {
        self.ok() && !self.selected.is_empty()
    }
    fn named(&self) -> bool {
        self.ok() && self.selected.contains(&self.hidden)
    }
    /// At ENR >= 2, where the headline figures are taken.
    fn strong(&self) -> bool {
        self.enr.unwrap_or(0.0) >= 2.0
    }
    /// Named with nothing else beside it.
    fn named_alone(&self) -> bool {
        self.named() && self.selected.len() == 1
    }
    fn heldout_change(&self) -> Option<f64> {
        match (self.loco_before, self.loco_after) {
            (Some(b), Some(a)) if b > 0.0 => Some(a / b - 1.0),
            _ => None,
        }
    }
}

/// 95 % Wilson score interval of k successes in n.
pub fn wilson(k: usize, n: usize) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let (z, nf) = (1.96f64, n as f64);
    let p = k as f64 / nf;
    let den = 1.0 + z * z / nf;
    let centre = (p + z * z / (2.0 * nf)) / den;
    let half = z * (p * (1.0 - p) / nf + z * z / (4.0 * nf * nf)).sqrt() / den;
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

fn pct(k: usize, n: usize) -> String {
    if n == 0 {
        "-".into()
    } else {
        format!("{k}/{n} = {:.0} %", 100.0 * k as f64 / n as f64)
    }
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) })
}

fn fmt_pct(x: Option<f64>) -> String {
    x.map_or("-".into(), |x| format!("{:+.0} %", 100.0 * x))
}

/// The generation summary of one family (`--generate-only`): datasets per kind, generation failures
/// with their reasons, and per mechanism the count at ENR >= 2 and the median ENR and ENR beyond
/// nuisance, and how many at ENR >= 2 a rival reproduces (`detectable::nearest_rival`: sum of
/// squares < 2).
pub fn generation_summary(family: &str, outcomes: &[Outcome]) -> String {
    let median = |v: Vec<f64>| median(v).map_or_else(|| "-".to_string(), |m| format!("{m:.2}"));
    let failed: Vec<&Outcome> = outcomes.iter().filter(|o| o.status == "generation_failed").collect();
    let mut s = format!(
        "family {family}: {} datasets, {} generated, {} generation failures\n",
        outcomes.len(),
        outcomes.len() - failed.len(),
        failed.len()
    );
    for o in &failed {
        s.push_str(&format!("  failed {:03} {}: {}\n", o.index, o.hidden, o.reason));
    }
    s.push_str(
        "  kind                 n  failed  ENR>=2  median ENR  median ENR beyond nuisance  ENR>=2 a rival reproduces (leaves < 2)\n",
    );
    let kinds = std::iter::once("null").chain(MECHANISMS).chain(DECOYS);
    for k in kinds {
        let of: Vec<&Outcome> = outcomes.iter().filter(|o| o.hidden == k).collect();
        let ok: Vec<&&Outcome> = of.iter().filter(|o| o.status != "generation_failed").collect();
        let strong = ok.iter().filter(|o| o.enr.is_some_and(|e| e >= 2.0)).count();
        let confusable =
            ok.iter().filter(|o| o.enr.is_some_and(|e| e >= 2.0) && o.rival_chi2.is_some_and(|e| e < 2.0)).count();
        s.push_str(&format!(
            "  {k:<18} {:>3} {:>7} {:>7} {:>11} {:>27} {:>38}\n",
            of.len(),
            of.len() - ok.len(),
            strong,
            median(ok.iter().filter_map(|o| o.enr).collect()),
            median(ok.iter().filter_map(|o| o.enr_beyond_nuisance).collect()),
            confusable,
        ));
    }
    s
}

/// Headline numbers of one family (also in `scores.json`).
#[derive(Debug, Clone, Serialize)]
pub struct Headline {
    /// Family.
    pub family: String,
    /// Nulls with a mechanism selected, of all nulls.
    pub false_positives: [usize; 2],
    /// Wilson 95 % interval of the false-positive rate.
    pub fp_wilson: (f64, f64),
    /// Correct names at ENR >= 2, of all mechanism datasets at ENR >= 2.
    pub named_enr2: [usize; 2],
    /// Correct names over every ENR.
    pub named_all: [usize; 2],
    /// Decoys with no mechanism selected.
    pub decoys_abstained: [usize; 2],
    /// Median held-out RMS change where a mechanism is claimed on a mechanism dataset.
    pub heldout_claimed: Option<f64>,
    /// Median held-out RMS change on nulls.
    pub heldout_nulls: Option<f64>,
    /// Generation failures and diagnosis errors.
    pub failures: [usize; 2],
}

/// The markdown section of one family, and its headline.
pub fn summarise(family: &str, outcomes: &[Outcome]) -> (String, Headline) {
    let mut s = String::new();
    let of = |k: &str| outcomes.iter().filter(|o| o.hidden == k).collect::<Vec<_>>();
    let gen_failed = outcomes.iter().filter(|o| o.status == "generation_failed").count();
    let diag_err = outcomes.iter().filter(|o| o.status == "diagnosis_error").count();
    let _ = writeln!(
        s,
        "{} datasets: {} generated, {gen_failed} generation failures, {diag_err} diagnosis errors (each listed in `outcomes.json`).\n",
        outcomes.len(),
        outcomes.len() - gen_failed
    );
    // False positives.
    let nulls: Vec<_> = of("null").into_iter().filter(|o| o.status != "generation_failed").collect();
    let fp = nulls.iter().filter(|o| o.claims()).count();
    let (lo, hi) = wilson(fp, nulls.len());
    let _ = writeln!(
        s,
        "**False positives** (a null with any mechanism in `selected`): {} (95 % Wilson interval {:.1}-{:.1} %).\n",
        pct(fp, nulls.len()),
        100.0 * lo,
        100.0 * hi
    );
    // Naming.
    let mech: Vec<&Outcome> = outcomes
        .iter()
        .filter(|o| MECHANISMS.contains(&o.hidden.as_str()) && o.status != "generation_failed")
        .collect();
    let strong = |o: &&&Outcome| o.strong();
    let n2 = mech.iter().filter(strong).count();
    let k2 = mech.iter().filter(strong).filter(|o| o.named()).count();
    let kall = mech.iter().filter(|o| o.named()).count();
    let _ = writeln!(
        s,
        "**Correct naming** (`selected` contains the hidden id): at ENR >= 2 {}; over every ENR {}.\n",
        pct(k2, n2),
        pct(kall, mech.len())
    );
    let a2 = mech.iter().filter(strong).filter(|o| o.named_alone()).count();
    let _ = writeln!(
        s,
        "**Named alone** (`selected` is exactly the hidden id): at ENR >= 2 {}; over every ENR {}.\n",
        pct(a2, n2),
        pct(mech.iter().filter(|o| o.named_alone()).count(), mech.len())
    );
    let beyond = |o: &&&Outcome| o.enr_beyond_nuisance.unwrap_or(0.0) >= 2.0;
    let nb = mech.iter().filter(beyond).count();
    let kb = mech.iter().filter(beyond).filter(|o| o.named()).count();
    let _ = writeln!(
        s,
        "Of these, the datasets whose effect the stated nuisance cannot absorb (ENR beyond nuisance >= 2, \
         `detectable.rs`, from the generator's truth alone): {} named; {} of the ENR >= 2 datasets are such.\n",
        pct(kb, nb),
        pct(mech.iter().filter(strong).filter(beyond).count(), n2)
    );
    let _ = writeln!(s, "| mechanism | named at ENR >= 2 | named, all ENR | truth in `selected` or `ambiguous_with`, all ENR | named at ENR beyond nuisance >= 2 | median ENR (shape ENR; beyond nuisance) |");
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for id in MECHANISMS {
        let rows: Vec<&&Outcome> = mech.iter().filter(|o| o.hidden == id).collect();
        let st: Vec<&&&Outcome> = rows.iter().filter(|o| o.strong()).collect();
        let in_set = rows.iter().filter(|o| o.ok() && (o.named() || o.ambiguous_with.contains(&o.hidden))).count();
        let bo: Vec<&&Outcome> = rows.iter().copied().filter(|o| beyond(o)).collect();
        let _ = writeln!(
            s,
            "| {id} | {} | {} | {} | {} | {:.1} ({:.1}; {}) |",
            pct(st.iter().filter(|o| o.named()).count(), st.len()),
            pct(rows.iter().filter(|o| o.named()).count(), rows.len()),
            pct(in_set, rows.len()),
            pct(bo.iter().filter(|o| o.named()).count(), bo.len()),
            median(rows.iter().filter_map(|o| o.enr).collect()).unwrap_or(0.0),
            median(rows.iter().filter_map(|o| o.enr_shape).collect()).unwrap_or(0.0),
            median(rows.iter().filter_map(|o| o.enr_beyond_nuisance).collect())
                .map_or_else(|| "not available".to_string(), |v| format!("{v:.1}"))
        );
    }
    misses_by_cause(&mut s, &mech);
    by_shadow_fidelity(&mut s, &mech, &nulls);
    // Naming against ENR, and against the ENR beyond the stated nuisance.
    let bins = [(0.0, 1.0, "[0, 1)"), (1.0, 2.0, "[1, 2)"), (2.0, 4.0, "[2, 4)"), (4.0, f64::INFINITY, ">= 4")];
    binned(&mut s, "ENR", &bins, &mech, |o| o.enr.or(Some(0.0)));
    binned(&mut s, "ENR beyond nuisance", &bins, &mech, |o| o.enr_beyond_nuisance);
    by_rival(&mut s, &mech);
    let na = mech.iter().filter(|o| o.enr_beyond_nuisance.is_none()).count();
    if na > 0 {
        let _ = writeln!(s, "\n{na} mechanism datasets have no ENR beyond nuisance (a perturbed solve failed).");
    }
    // Confusion matrix.
    let _ = writeln!(s, "\n**Confusion matrix** (rows: hidden; columns: the verdict when nothing is selected, else each selected mechanism; `multi` counts datasets with 2+ selected):\n");
    let mut head = String::from("| hidden | n | none | unexplained | ambiguous |");
    for id in MECHANISMS {
        let _ = write!(head, " {id} |");
    }
    head.push_str(" multi | diagnosis error | generation failed |");
    let _ = writeln!(s, "{head}");
    let _ = writeln!(s, "|{}", "---|".repeat(4 + 1 + MECHANISMS.len() + 3));
    let kinds: Vec<&str> = std::iter::once("null").chain(MECHANISMS).chain(DECOYS).collect();
    for kind in kinds {
        let rows = of(kind);
        let verdict = |v: &str| {
            rows.iter().filter(|o| o.ok() && o.selected.is_empty() && o.verdict.as_deref() == Some(v)).count()
        };
        let mut line = format!(
            "| {kind} | {} | {} | {} | {} |",
            rows.len(),
            verdict("none"),
            verdict("unexplained"),
            verdict("ambiguous")
        );
        for id in MECHANISMS {
            let _ = write!(line, " {} |", rows.iter().filter(|o| o.ok() && o.selected.iter().any(|x| x == id)).count());
        }
        let _ = write!(
            line,
            " {} | {} | {} |",
            rows.iter().filter(|o| o.ok() && o.selected.len() > 1).count(),
            rows.iter().filter(|o| o.status == "diagnosis_error").count(),
            rows.iter().filter(|o| o.status == "generation_failed").count()
        );
        let _ = writeln!(s, "{line}");
    }
    // Decoys.
    let dec: Vec<&Outcome> =
        outcomes.iter().filter(|o| DECOYS.contains(&o.hidden.as_str()) && o.status != "generation_failed").collect();
    let abst = dec.iter().filter(|o| o.ok() && o.selected.is_empty()).count();
    let _ = write!(
        s,
        "\n**Decoys abstained** (no mechanism selected; a diagnosis error does not count as abstention): {}",
        pct(abst, dec.len())
    );
    for d in DECOYS {
        let r: Vec<_> = dec.iter().filter(|o| o.hidden == d).collect();
        let _ = write!(s, "; {d} {}", pct(r.iter().filter(|o| o.ok() && o.selected.is_empty()).count(), r.len()));
    }
    let _ = writeln!(s, ".\n");
    // Held-out.
    let claimed_mech: Vec<f64> = mech.iter().filter(|o| o.claims()).filter_map(|o| o.heldout_change()).collect();
    let claimed_all: Vec<f64> = outcomes.iter().filter(|o| o.claims()).filter_map(|o| o.heldout_change()).collect();
    let null_ch: Vec<f64> = nulls.iter().filter(|o| o.ok()).filter_map(|o| o.heldout_change()).collect();
    let worst = null_ch.iter().copied().fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))));
    let _ = writeln!(
        s,
        "**Held-out (leave-one-condition-out) RMS change**, `fit.after.loco.all / fit.before.loco.all - 1`:\n"
    );
    let _ = writeln!(
        s,
        "- mechanism datasets where a mechanism is claimed: n = {}, median {}",
        claimed_mech.len(),
        fmt_pct(median(claimed_mech.clone()))
    );
    let _ = writeln!(
        s,
        "- every dataset where a mechanism is claimed: n = {}, median {}",
        claimed_all.len(),
        fmt_pct(median(claimed_all))
    );
    let _ = writeln!(
        s,
        "- nulls: n = {}, median {}, worst {}",
        null_ch.len(),
        fmt_pct(median(null_ch.clone())),
        fmt_pct(worst)
    );
    let secs: Vec<f64> = outcomes.iter().filter(|o| o.ok()).map(|o| o.seconds).collect();
    let _ = writeln!(s, "\nMedian diagnosis time {:.2} s per dataset.", median(secs).unwrap_or(0.0));
    let head = Headline {
        family: family.into(),
        false_positives: [fp, nulls.len()],
        fp_wilson: (lo, hi),
        named_enr2: [k2, n2],
        named_all: [kall, mech.len()],
        decoys_abstained: [abst, dec.len()],
        heldout_claimed: median(claimed_mech),
        heldout_nulls: median(null_ch),
        failures: [gen_failed, diag_err],
    };
    (s, head)
}

#[cfg(test)]
mod tests {
    use super::breakdown::miss_cause;
    use super::*;

    fn outcome(hidden: &str, bn: f64, selected: &[&str], ambiguous: &[&str]) -> Outcome {
        Outcome {
            family: "a".into(),
            index: 0,
            hidden: hidden.into(),
            enr: Some(3.0),
            enr_shape: None,
            enr_beyond_nuisance: Some(bn),
            rival_chi2: None,
            nearest_rival: None,
            status: "ok".into(),
            reason: String::new(),
            verdict: Some(if selected.is_empty() { "none" } else { "missing_physics" }.into()),
            selected: selected.iter().map(|s| (*s).into()).collect(),
            ambiguous_with: ambiguous.iter().map(|s| (*s).into()).collect(),
            loco_before: None,
            loco_after: None,
            shadow_rms_pct: None,
            seconds: 0.0,
        }
    }

    #[test]
    fn misses_are_sorted_by_cause() {
        let h = "heat_partition";
        assert_eq!(miss_cause(&outcome(h, 0.5, &[h], &[])), None);
        assert_eq!(miss_cause(&outcome(h, 3.0, &[], &[h, "thermal_softening"])), Some(0));
        assert_eq!(miss_cause(&outcome(h, 0.5, &["thermal_softening"], &[])), Some(1));
        assert_eq!(miss_cause(&outcome(h, 0.5, &[], &[])), Some(2));
        assert_eq!(miss_cause(&outcome(h, 1.0, &[], &[])), Some(3));
        let mut err = outcome(h, 3.0, &[], &[]);
        err.status = "diagnosis_error".into();
        assert_eq!(miss_cause(&err), Some(4));
        let rows = [outcome(h, 0.5, &[h], &[]), outcome(h, 0.5, &[], &[]), outcome(h, 3.0, &["size_effect"], &[])];
        let refs: Vec<&Outcome> = rows.iter().collect();
        let mut s = String::new();
        misses_by_cause(&mut s, &refs);
        assert!(s.contains("| heat_partition | 2/3 | 0 | 1 | 1 | 0 | 0 |"), "{s}");
        assert!(s.contains("| all | 2/3 | 0 | 1 | 1 | 0 | 0 |"), "{s}");
    }

    #[test]
    fn naming_is_binned_by_the_shadow_fit() {
        let h = "size_effect";
        let with = |rms: Option<f64>, selected: &[&str], hidden: &str| {
            let mut o = outcome(hidden, 3.0, selected, &[]);
            o.shadow_rms_pct = rms;
            o
        };
        let mech = [with(Some(1.0), &[h], h), with(Some(2.9), &[], h), with(Some(7.0), &[h], h), with(None, &[h], h)];
        let nulls = [with(Some(12.0), &[], "null"), with(Some(12.5), &["edge_ploughing"], "null")];
        let (m, n): (Vec<&Outcome>, Vec<&Outcome>) = (mech.iter().collect(), nulls.iter().collect());
        let mut s = String::new();
        by_shadow_fidelity(&mut s, &m, &n);
        assert!(s.contains("| below 3 % | 1/2 = 50 % | - |"), "{s}");
        assert!(s.contains("| 6-10 % | 1/1 = 100 % | - |"), "{s}");
        assert!(s.contains("| 10 % and above | - | 1/2 = 50 % |"), "{s}");
        assert!(s.contains("1 mechanism datasets at ENR >= 2 have no shadow"), "{s}");
    }

    #[test]
    fn wilson_by_hand() {
        // 8 of 56: p 0.142857; z^2/n = 0.0686; centre (0.142857 + 0.0343) / 1.0686 = 0.16578;
        // half 1.96 sqrt(0.0021866 + 0.00030625) / 1.0686 = 0.09162 -> 0.0742-0.2574.
        let (lo, hi) = wilson(8, 56);
        assert!((lo - 0.0742).abs() < 5e-4 && (hi - 0.2574).abs() < 5e-4, "{lo} {hi}");
    }
}
