//! The library table (design note Sec 2.2): for each mechanism its title, source, parameters
//! (units, bounds, off value, typical magnitude), in-model hook, expected signature, covariates,
//! confounders and the measurement that would separate them. The functions that act on these
//! entries are in the parent module.

use super::{MechanismId, MechanismInfo, ParamInfo};
use crate::hooks::Hook;

/// The library entry of `id`.
#[must_use]
pub fn info(id: MechanismId) -> MechanismInfo {
    use MechanismId as M;
    let p = |name, unit, lower, upper, off, typical| ParamInfo { name, unit, lower, upper, off, typical };
    match id {
        M::EdgePloughing => MechanismInfo {
            id,
            title: "cutting-edge ploughing (edge radius rubbing the machined surface)",
            source: "Waldorf, DeVor & Kapoor 1998 slip-line ploughing; the edge's chord effective rake after Manjunathaiah & Endres 2000 (cutcal_model::oxley::edge); design note M1",
            // The effective edge radius; with `edge_radius_um` recorded, the per-test radius keeps the
            // recorded shape: r_i = r_e r_rec,i / mean(r_rec).
            // w_rake is the share of the edge's effective rake the chip formation sees: 0 = the
            // ploughing forces alone (Waldorf et al. 1998, chip formation on the nominal rake), 1 = the
            // chip also forms on the chord of the edge above the stagnation point (Manjunathaiah &
            // Endres 2000; `EdgePloughing::effective_rake_rad`), which thickens the chip and raises Ft
            // most at small h/r_e. It has no effect at r_e = 0 (a shape parameter, `screen::shape_params`).
            params: vec![p("r_e", "um", 0.0, 80.0, 0.0, 15.0), p("w_rake", "-", 0.0, 1.0, 0.0, 1.0)],
            hook: Some(Hook::EdgeRadius),
            signature: "Fc +, Ft ++ (relative residual grows as r_e/h); chip unchanged with ploughing alone (w_rake = 0), thicker at small h when the edge's effective rake acts (w_rake > 0)",
            covariates: "uncut chip thickness; edge radius helps",
            confounders: &[M::FlankWear, M::SizeEffect, M::ForceCrosstalk],
            separate_by: "add a smaller and a larger feed (ploughing is additive: its relative share grows as 1/h) and measure the edge radius",
        },
        M::FlankWear => MechanismInfo {
            id,
            title: "flank wear land contact",
            source: "Smithey, Kapoor & DeVor 2001 wear-land model (cutcal_model::oxley::edge); design note M3",
            // VB at the most worn test; VB_i = VB (w_0 + (1 - w_0) x wear state), the wear state
            // measured VB / max, else order / max. w_0 (at most 0.5) is the share of the final VB
            // present from the first test: the classical wear curve's fast running-in before its
            // steady growth (tool-life testing, ISO 3685:1993 Annex G). Without it a running-in
            // land's constant part went to an edge radius and its trend was then held back as the
            // edge's confounder (thirtieth session, family o). A shape parameter: no effect at VB = 0.
            params: vec![p("vb", "mm", 0.0, 0.4, 0.0, 0.1), p("w_0", "-", 0.0, 0.5, 0.0, 0.2)],
            hook: Some(Hook::WearLand),
            signature: "Fc +, Ft ++ growing with test order / measured VB (from a running-in share at the first test), chip thickness unchanged",
            covariates: "flank wear VB per test, or the test order",
            // Cross-talk too: the land's normal-to-shear stress ratio differs between wear-land
            // models (Smithey et al.'s profiles here, Teitenberg et al. 1992's uniform stresses,
            // Waldorf 1996's plastic-then-elastic land), so an Ft excess in proportion to Fc left
            // after a wear claim is as likely the land's true ratio as an instrument error.
            confounders: &[M::EdgePloughing, M::ForceCrosstalk],
            separate_by: "measure VB after each test and randomise the test order",
        },
        M::ToolChipFriction => MechanismInfo {
            id,
            title: "tool-chip friction below full sticking (sliding region), falling with speed or capped by Coulomb friction",
            source: "Zorev 1963; Oxley 1989; Rech, Claudin & D'Eramo 2009; Oezel 2006 (hybrid Coulomb-Tresca law); design note M4, M5",
            // m_f = m_f0 (V / V_ref)^(-p_v), V_ref the geometric mean test speed (note M5). The
            // lower bound 0.2 of m_f0 admits the mean Zorev interface shear of note M4 with a short
            // sticking zone (a sticking fraction 0.2 and mu = 0.25 under its sigma_n = sigma_max
            // (1 - x/l_c)^2.5 give about 0.28 k_chip); p_v <= 0.5 is note M5's range.
            // Two forms of the law (thirty-third session), each refitted and the lower objective
            // kept (`screen::coulomb_form`, `Context::friction_coulomb`): the shear-factor law
            // m_f k_chip, and the hybrid Coulomb-Tresca law min(mu sigma_N, k_chip) of DEFORM and
            // Abaqus (Oezel 2006), which slides where the baseline interface needs the most
            // friction to stick (a cool chip on a hard primary zone: thin cuts, low speeds) and
            // sticks unchanged where it needs little (`mechanism::hybrid_friction_factor`). With
            // the shear-factor law alone a hybrid law's reduction, largest on the coolest
            // interfaces, was named a built-up edge (family o, OxleyPython: 2-4 of 12 frictions
            // named). The same two parameters in both: the form is a choice between two models,
            // as between two mechanisms, not a third parameter.
            params: vec![p("m_f0", "-", 0.2, 1.0, 1.0, 0.85), p("p_v", "-", 0.0, 0.5, 0.0, 0.15)],
            hook: Some(Hook::FrictionFactor),
            signature: "Fc - (mild), Ft --, chip thinner; Ft/Fc falling with ln V when p_v > 0; with the hybrid Coulomb-Tresca form most where the baseline's apparent friction F/N is highest",
            covariates: "none for m_f0; p_v needs at least two speeds",
            confounders: &[M::ThermalSoftening, M::ForceCrosstalk],
            separate_by: "measure the chip thickness (mass-based) and the contact length; a channel-gain error does not move the chip",
        },
        M::ThermalSoftening => MechanismInfo {
            id,
            title: "thermomechanical softening different from the model's (stronger or weaker)",
            source: "Ertuerk, Malakizadi & Larsson 2020 (coupling k_T); Johnson & Cook 1983 (exponent m); design note M7",
            // Two forms, both two-sided: k_T scales the temperature rise the flow stress sees
            // (k_T < 0 weaker softening, > 0 stronger); ln_m scales the JC thermal exponent m
            // beyond the nuisance's +-5 % (a thermal exponent fitted at other temperatures, the
            // commonest source of a wrong softening). Together they span softening that is more
            // level-like (ln_m) or more temperature-selective (k_T) than the JC law's.
            params: vec![p("k_T", "-", -0.5, 1.5, 0.0, 0.2), p("ln_m", "-", -0.7, 0.7, 0.0, 0.2)],
            hook: Some(Hook::ExtraSoftening),
            signature: "k_T: forces over-predicted increasingly with speed and feed, Ft most, chip thinner; ln_m: mostly a force level with a mild trend in temperature",
            covariates: "a speed range of about a decade",
            confounders: &[M::HeatPartition, M::ToolChipFriction],
            separate_by: "widen the speed range (x10) and measure the interface temperature",
        },
        M::HeatPartition => MechanismInfo {
            id,
            title: "heat partition different from Oxley's: into the workpiece at the shear plane, into the tool at the interface",
            source: "Boothroyd 1963; Oxley 1989; Loewen & Shaw 1954; Komanduri & Hou 2001; design note M6",
            // k_beta scales Boothroyd's shear-plane share into the work, up to 3 (beta itself capped
            // at 1): Boothroyd's correlation gives 0.1-0.3 at the thermal numbers of practical
            // cutting, and a partition from another heat-source model (e.g. Loewen & Shaw 1954's
            // shear-plane share) can differ from it by a factor; at 1.8 estimates were pinned at the
            // bound. s_int is the share of the tool-chip frictional heat that enters the chip, which
            // Oxley takes as 1: Loewen & Shaw 1954 and Komanduri & Hou 2001 give the tool 10-50 % of
            // it at low chip speeds (0.5-0.9); above 1 (to 1.5) covers a dT_M correlation that runs low.
            params: vec![p("k_beta", "-", 0.4, 3.0, 1.0, 1.3), p("s_int", "-", 0.3, 1.5, 1.0, 0.8)],
            hook: Some(Hook::HeatPartition),
            signature: "k_beta: force residual that follows the thermal number V h (largest at low V h); s_int: interface temperature and chip-side flow stress, so Ft and the chip",
            covariates: "temperature measurement to separate it from JC m",
            confounders: &[M::ThermalSoftening, M::ToolChipFriction],
            separate_by: "measure the tool-chip interface temperature",
        },
        M::SizeEffect => MechanismInfo {
            id,
            title: "size effect (strengthening at small uncut chip thickness)",
            source: "Nix & Gao 1998; Joshi & Melkote 2004; design note M10",
            // Up to 3000 um: with l >> h the factor tends to sqrt(l/h), so the same form also covers
            // power-law (Kienzle-type) size effects of exponent up to 1/2 over a feed range; the
            // local exponent 0.5 (l/h) / (1 + l/h) is 0.45 at l/h = 10, i.e. h = 0.3 mm (a bound
            // of 300 um capped it at 0.25 there, and left strong size effects unexplained).
            // w_chip is the share of the strengthening the chip's flow stress at the interface takes:
            // 1 = every flow stress (Nix & Gao 1998 applied to the material), 0 = the primary shear
            // zone only (Joshi & Melkote 2004 apply the strain gradient to the primary zone, whose
            // thickness scales with h). The primary zone's strengthening over the chip's is absolute:
            // in Oxley's closure k_chip enters only tau_int = m_f k_chip, so the primary zone alone
            // strengthened by F = sqrt(1 + l/h) is every flow stress times F with the interface
            // factor times F^(w_chip - 1) (at most 1).
            // w_ref (thirty-second session) is the share of the strengthening at the dataset's
            // geometric-mean thickness h_ref that the simulation's flow stress already holds:
            // 1 = a flow stress set at these thicknesses (the factor relative to h_ref, no level of
            // its own there; a JC set identified from cuts like these), 0 = the bulk material's (the
            // absolute factor, a strengthening at every thickness; a JC set from compression or
            // Hopkinson-bar tests). The level then comes with the trend through the one length l,
            // never alone: a level the baseline cannot absorb (`nuisance::level_bound`) is not left
            // to a thermal mechanism. Like w_chip, a shape parameter (`screen::shape_params`).
            params: vec![
                p("l_um", "um", 0.0, 3000.0, 0.0, 5.0),
                p("w_chip", "-", 0.0, 1.0, 1.0, 0.0),
                p("w_ref", "-", 0.0, 1.0, 1.0, 0.0),
            ],
            hook: Some(Hook::FlowMultiplier),
            signature: "Fc and Ft up by the same factor at small h, Ft/Fc and chip unchanged (w_chip = 1); with the primary zone alone (w_chip < 1) the chip also thins and Ft/Fc falls at small h; with the bulk flow stress in the simulation (w_ref < 1) the forces are also up at every h",
            covariates: "at least three feeds",
            confounders: &[M::EdgePloughing, M::ToolChipFriction],
            separate_by: "add a second edge radius or a wider feed range: Ft/Fc stays flat for a size effect",
        },
        M::BuiltUpEdge => MechanismInfo {
            id,
            title: "built-up edge at low speed",
            source: "Trent & Wright 2000; Childs et al. 2000; design note M9",
            // The gate (`mechanism::bue_gates`): below an onset on the interface temperature (or the
            // speed), and, as a band, above a floor as well. Both are chosen on a grid and count
            // in the AICc. The edge's height rises from the slowest cuts to a peak and vanishes on a
            // hot interface (Trent & Wright 2000, Childs et al. 2000); with the one-sided gate alone
            // a band in the middle of the design (family d of the concealed benchmark: a window in
            // ln V whose peak falls with feed) was read as friction, softening or a heat partition
            // (0-2 of 12 named, thirty-fourth session).
            params: vec![p("d_alpha", "deg", 0.0, 25.0, 0.0, 8.0), p("v_onset", "m/min", 1.0, 1e4, 0.0, 100.0)],
            hook: Some(Hook::RakeShift),
            signature: "Fc -, Ft --, chip thinner, only on the coolest interfaces (lowest speeds and feeds), or in a band of them",
            covariates: "at least three speeds, two of them in the low-speed regime",
            confounders: &[M::ToolChipFriction],
            separate_by: "repeat the lowest-speed test twice and inspect the edge for adhered material",
        },
        M::ForceCrosstalk => MechanismInfo {
            id,
            title: "dynamometer cross-talk from the cutting-force channel into the feed channel",
            source: "ISO 21612:2021; design note M11",
            // Up to +-0.2: beyond a calibrated instrument's own cross-talk of a few per cent, a
            // measuring axis turned by theta against the cutting direction (tool holder or
            // dynamometer mounting) gives c = sin theta, 0.2 at 11.5 deg. At +-0.08 (4.6 deg) a
            // larger cross-talk was pinned at the bound and a second, spurious mechanism (edge
            // ploughing, softening) was claimed to carry the rest.
            params: vec![p("c_tc", "-", -0.2, 0.2, 0.0, 0.02)],
            hook: None,
            signature: "Ft shifted in proportion to Fc (grows with h), chip unchanged",
            covariates: "a wide feed range",
            confounders: &[M::EdgePloughing, M::FlankWear],
            separate_by: "check the dynamometer with dead weights in each direction",
        },
    }
}
