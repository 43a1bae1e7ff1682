//! The forms of a DPZD identification the CLI prints and `cutcal run` writes: the readable table,
//! the zone fields CSV (the data of the paper's Fig 4) and the JC file of an identified set (the
//! JSON form is the serialised [`crate::dpzd::DpzdIdentifyReport`]).

use std::fmt::Write as _;

use cutcal_model::dpzd::ZoneSolution;

use crate::dpzd::DpzdIdentifyReport;
use crate::error::Result;

/// The zone fields as CSV (the data behind the paper's Fig 4).
pub fn fields_csv(zone: &ZoneSolution, n: usize) -> Result<String> {
    let mut out = String::from("x_mm,gamma,gamma_dot_per_s,eps,eps_dot_per_s,tau_mpa,sigma_eff_mpa,temperature_c\n");
    for p in zone.profile(n)? {
        writeln!(
            out,
            "{:.6},{:.6},{:.6e},{:.6},{:.6e},{:.4},{:.4},{:.4}",
            p.x_m * 1e3,
            p.gamma,
            p.gamma_dot_per_s,
            p.strain,
            p.strain_rate_per_s,
            p.tau_pa / 1e6,
            p.effective_stress_pa / 1e6,
            p.temperature_c
        )?;
    }
    Ok(out)
}

/// A JC file (TOML) for an identified set.
pub fn jc_toml(jc: &cutcal_model::JcParams, source: String) -> Result<String> {
    Ok(toml::to_string(&cutcal_io::jc_file::JcFile::from_params(jc, Some(source)))?)
}

/// Human-readable table of a report.
#[must_use]
pub fn render_table(r: &DpzdIdentifyReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "cutcal identify: {} test {} ({:?} DPZD, h = {:.4} mm, r = {})",
        r.material, r.test, r.model, r.h_mm, r.r
    );
    let _ = writeln!(s, "  {}", r.preset_note);
    match r.quadrature_nodes {
        Some(n) => {
            let _ = writeln!(s, "  quadrature nodes   {n:>10}");
        }
        None => {
            let _ = writeln!(s, "  fit points N       {:>10}", r.points);
        }
    }
    let _ = writeln!(s, "  shear angle        {:>10.2} deg", r.shear_angle_deg);
    let _ = writeln!(s, "  tau_max (Eq 9)     {:>10.1} MPa", r.tau_max_mpa);
    let _ = writeln!(s, "  max eff. strain    {:>10.3}", r.max_effective_strain);
    let _ = writeln!(s, "  max eff. rate      {:>10.3e} 1/s", r.max_effective_strain_rate_per_s);
    let _ = writeln!(s, "  T_AB               {:>10.1} degC", r.t_ab_c);
    let _ = writeln!(s, "  T_EF               {:>10.1} degC   ({} fixed-point iterations)", r.t_ef_c, r.iterations);
    let _ = writeln!(s, "  parameter      value   note");
    let note = |name: &str| if r.at_bounds.iter().any(|a| a == name) { "at bound" } else { "" };
    let _ = writeln!(s, "  A [MPa]     {:>10.2}   {}", r.jc.a_mpa, note("a_mpa"));
    let _ = writeln!(s, "  B [MPa]     {:>10.2}   {}", r.jc.b_mpa, note("b_mpa"));
    let _ = writeln!(s, "  n           {:>10.4}   {}", r.jc.n, note("n"));
    let _ = writeln!(s, "  C           {:>10.5}   {}", r.jc.c, note("c"));
    let _ = writeln!(s, "  m           {:>10.4}   {}", r.jc.m, note("m"));
    let _ = writeln!(
        s,
        "  (no std.err: s^2 (J^T J)^-1 of deterministic model residuals has no statistical meaning; use --bootstrap N for a Monte-Carlo spread)"
    );
    let _ = writeln!(s, "  eps0 = {} 1/s, Tm = {} degC, Tr = {} degC", r.jc.eps0_per_s, r.jc.tm_c, r.jc.tr_c);
    let _ = writeln!(s, "  h = {:.4} mm: {}", r.h_mm, r.h_source);
    if r.h_history_mm.len() > 1 {
        let steps: Vec<String> = r.h_history_mm.iter().map(|h| format!("{h:.4}")).collect();
        let _ = writeln!(s, "  h fixed point [mm]: {}", steps.join(" -> "));
    }
    if !r.h_sensitivity.is_empty() {
        let _ = writeln!(s, "  h sensitivity (A, B and C only reparametrise with h; n and m do not):");
        for row in &r.h_sensitivity {
            match (row.a_mpa, row.b_mpa, row.c) {
                (Some(a), Some(b), Some(c)) => {
                    let _ = writeln!(s, "    h {:>8.4} mm: A {:>8.2} MPa, B {:>8.2} MPa, C {:.5}", row.h_mm, a, b, c);
                }
                _ => {
                    let _ =
                        writeln!(s, "    h {:>8.4} mm: {}", row.h_mm, row.note.as_deref().unwrap_or("not available"));
                }
            }
        }
    }
    let _ = writeln!(
        s,
        "  objective (Eq 15) {:.2} MPa, RMS {:.2} MPa; {}{}/{} local searches reached the best minimum (seed {}){}",
        r.objective_mpa,
        r.rms_mpa,
        match r.critical_distance {
            Some(rk) if r.filtered_starts > 0 => format!(
                "{} sample points, {} not searched (a better sample point within the MLSL critical distance {:.2}); ",
                r.starts, r.filtered_starts, rk
            ),
            _ => String::new(),
        },
        r.starts_at_best,
        r.starts - r.filtered_starts,
        r.seed,
        if r.stopped_starts > 0 {
            format!(
                "; {} of the searches were stopped on joining a minimum an earlier search had found ({} the best), \
                 by the multistart basin rule",
                r.stopped_starts, r.stopped_at_best
            )
        } else {
            String::new()
        }
    );
    if r.unconverged_starts > 0 {
        let _ = writeln!(
            s,
            "  {} of {} starts stopped at the LM iteration cap and were excluded",
            r.unconverged_starts, r.starts
        );
    }
    if let Some(c) = &r.correlation {
        let _ = writeln!(s, "  correlation of free parameters {:?}:", r.free);
        for row in c {
            let cells: Vec<String> = row.iter().map(|v| format!("{v:>7.3}")).collect();
            let _ = writeln!(s, "    {}", cells.join(" "));
        }
    }
    s
}
