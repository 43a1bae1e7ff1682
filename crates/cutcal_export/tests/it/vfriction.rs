//! The exported VFRICTION source compiled with gfortran and called by a driver with the argument
//! order of the Abaqus User Subroutines Reference (VFRICTION, Abaqus/Explicit): the friction force
//! it returns must be Eq 17 with the local k(T) of the JC set, at several pressures and temperatures.
//!
//! The expected values are computed here from paper Eq 17 and Eqs 14/16 written out in the test
//! (not through cutcal_export), so the check does not use the code it checks.

use std::process::Command;

use cutcal_export::{render, Dialect};

use crate::common;

/// A stub of Abaqus' `vaba_param.inc`: double precision implicit typing, as Abaqus/Explicit's
/// double-precision build defines it.
const VABA_PARAM: &str = "      implicit real*8 (a-h,o-z)\n      parameter (nprecd=2)\n";

/// Contact points: (normal force [N], contact area [mm^2], slave temperature [K], stick force [N]).
/// Stick forces are large so the Eq 17 limit is returned, except the last point, which sticks.
const POINTS: [(f64, f64, f64, f64); 6] = [
    (0.5, 0.01, 293.15, 1e6),
    (2.0, 0.01, 573.15, 1e6),
    (5.0, 0.01, 873.15, 1e6),
    (10.0, 0.01, 1073.15, 1e6),
    (20.0, 0.01, 1273.15, 1e6),
    (5.0, 0.01, 873.15, 0.05),
];

fn driver(props: &[f64]) -> String {
    let mut s = String::new();
    s.push_str("      program drv\n      include 'vaba_param.inc'\n");
    s.push_str("      parameter (nb=6, nfd=2, nd=3, ns=1, nns=1, nsl=1, nms=4, np=12, nf=1)\n");
    s.push_str("      dimension ft(nfd,nb), st(ns,nns,nb), jslv(nsl,nb), jmst(nms,nb), props(np)\n");
    s.push_str("      dimension ds(nd,nb), fst(nb), ftp(nd,nb), fn(nb), ar(nb), dcn(nd,nb), dcs(nd,nb)\n");
    s.push_str("      dimension shs(nsl,nb), shm(nms,nb), cs(nd,nsl,nb), cm(nd,nms,nb)\n");
    s.push_str("      dimension vs(nd,nsl,nb), vm(nd,nms,nb), ts(nb), tmm(nb), fs(nf,nb), fm(nf,nb)\n");
    s.push_str("      dimension jfl(2), rda(4)\n      character*80 si, ss, sm\n");
    for (i, p) in props.iter().enumerate() {
        s.push_str(&format!("      props({}) = {:e}\n", i + 1, p).replace('e', "d"));
    }
    for (k, (f, a, t, stick)) in POINTS.iter().enumerate() {
        let k = k + 1;
        s.push_str(
            &format!(
                "      fn({k}) = {f:e}\n      ar({k}) = {a:e}\n      ts({k}) = {t:e}\n      fst({k}) = {stick:e}\n"
            )
            .replace('e', "d"),
        );
        s.push_str(&format!("      ft(1,{k}) = 99.d0\n      ft(2,{k}) = 99.d0\n"));
    }
    // Arguments in the documented order (Abaqus User Subroutines Reference, VFRICTION).
    s.push_str("      call vfriction(ft, st, nb, nb, 1, nns, nsl, nms, nfd, nd, ns, np, 1, nf,\n");
    s.push_str("     *  jfl, rda, si, ss, sm, jslv, jmst, props, ds, fst, ftp, fn, ar, dcn, dcs,\n");
    s.push_str("     *  shs, shm, cs, cm, vs, vm, ts, tmm, fs, fm)\n");
    s.push_str("      do 10 k = 1, nb\n         write(*,'(2ES24.15)') ft(1,k), ft(2,k)\n   10 continue\n      end\n");
    s
}

#[test]
fn gfortran_vfriction_returns_eq17_with_local_k() {
    let opts = common::options();
    let required = std::env::var("CUTCAL_REQUIRE_TOOLS").is_ok_and(|v| v == "1");
    if Command::new("gfortran").arg("--version").output().is_err() {
        assert!(!required, "gfortran not found (apt-get install -y gfortran) and CUTCAL_REQUIRE_TOOLS=1");
        eprintln!("gfortran not found: skipping the VFRICTION driver test (CI sets CUTCAL_REQUIRE_TOOLS=1)");
        return;
    }
    let mut checked = 0;
    for case in common::cases().into_iter().filter(|c| c.key != "42crmo4") {
        let prov = common::provenance(&case);
        let files = render(Dialect::Abaqus, &common::input(&case, &prov, &opts)).unwrap();
        let src = &files.iter().find(|f| f.name.ends_with("_abaqus_vfriction.f")).unwrap().contents;
        // The props lines of the header's *FRICTION card, as a user would paste them.
        let lines: Vec<&str> = src.lines().collect();
        let at = lines.iter().position(|l| l.contains("*FRICTION, USER=FRICTION, PROPERTIES=12")).unwrap();
        let props: Vec<f64> = lines[at + 1..at + 3]
            .iter()
            .flat_map(|l| l.trim_start_matches('C').split(','))
            .map(|x| x.trim().parse::<f64>().unwrap())
            .collect();
        assert_eq!(props.len(), 12, "{}: props {props:?}", case.key);
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("vaba_param.inc"), VABA_PARAM).unwrap();
        std::fs::write(dir.path().join("vfriction.f"), src).unwrap();
        std::fs::write(dir.path().join("drv.f"), driver(&props)).unwrap();
        // The subroutine is compiled as Abaqus compiles user code: fixed form, 72 columns, with a
        // truncated line an error; the driver may use long lines.
        let steps: [&[&str]; 3] = [
            &["-c", "-ffixed-form", "-std=legacy", "-Werror=line-truncation", "vfriction.f"],
            &["-c", "-ffixed-form", "-ffixed-line-length-none", "drv.f"],
            &["-o", "drv", "drv.o", "vfriction.o"],
        ];
        for args in steps {
            let out = Command::new("gfortran").args(args).current_dir(dir.path()).output().unwrap();
            let log = String::from_utf8_lossy(&out.stderr).to_string();
            assert!(out.status.success(), "{}: gfortran {args:?} failed:\n{log}", case.key);
        }
        let run = Command::new(dir.path().join("drv")).output().unwrap();
        assert!(run.status.success());
        let text = String::from_utf8(run.stdout).unwrap();
        let rows: Vec<[f64; 2]> = text
            .lines()
            .map(|l| {
                let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
                [v[0], v[1]]
            })
            .collect();
        assert_eq!(rows.len(), POINTS.len());
        // Independent Eq 17 with the JC law (paper Eqs 14, 16) at eps_r, rate_r, T, in t-mm-s-K.
        let (m0, beta, a, b, n, c, m) = (props[0], props[1], props[2], props[3], props[4], props[5], props[6]);
        let (eps0, tr, tm, er, rr) = (props[7], props[8], props[9], props[10], props[11]);
        assert!((a - case.jc.a_pa * 1e-6).abs() < 1e-6 * a, "{}: A in MPa", case.key);
        for (k, (f, area, t, stick)) in POINTS.iter().enumerate() {
            let theta = ((t - tr) / (tm - tr)).clamp(0.0, 1.0);
            let kt = (a + b * er.powf(n)) * (1.0 + c * (rr / eps0).max(1.0).ln()) * (1.0 - theta.powf(m)) / 3f64.sqrt();
            let p = f / area;
            let limit = m0 * (1.0 - (-beta * p).exp()) * kt * area;
            let expect = -limit.min(*stick);
            let got = rows[k][0];
            assert!(
                (got - expect).abs() <= 1e-9 * expect.abs().max(1e-12),
                "{} point {k}: P = {p} MPa, T = {t} K: VFRICTION {got} N vs Eq 17 {expect} N",
                case.key
            );
            assert!(rows[k][1].abs() < 1e-300, "{} point {k}: second tangent direction must be 0", case.key);
            checked += 1;
        }
    }
    assert_eq!(checked, 12);
}
