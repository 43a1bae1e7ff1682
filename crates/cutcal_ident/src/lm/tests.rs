//! Unit tests of `lm`.

use super::*;

/// Rosenbrock as least squares: r = (10 (y - x^2), 1 - x); minimum (1, 1).
pub(crate) struct Rosen;
impl Problem for Rosen {
    fn parameter_count(&self) -> usize {
        2
    }
    fn residual_count(&self) -> usize {
        2
    }
    fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
        out[0] = 10.0 * (p[1] - p[0] * p[0]);
        out[1] = 1.0 - p[0];
        Ok(())
    }
}

#[test]
fn finds_rosenbrock_minimum_inside_box() {
    let b = Bounds::new(vec!["x".into(), "y".into()], vec![-2.0, -1.0], vec![2.0, 3.0]).unwrap();
    let r = minimise(&Rosen, &b, &DVector::from_vec(vec![-1.2, 1.0]), &LmOptions::precise()).unwrap();
    assert!((r.params[0] - 1.0).abs() < 1e-7 && (r.params[1] - 1.0).abs() < 1e-7, "{:?}", r.params);
}

#[test]
fn stops_on_an_active_bound() {
    // Box x <= 0.5: the constrained minimum of Rosenbrock is at x = 0.5, y = 0.25 (r0 = 0 there).
    let b = Bounds::new(vec!["x".into(), "y".into()], vec![-2.0, -1.0], vec![0.5, 3.0]).unwrap();
    let r = minimise(&Rosen, &b, &DVector::from_vec(vec![-1.2, 1.0]), &LmOptions::precise()).unwrap();
    assert!((r.params[0] - 0.5).abs() < 1e-9 && (r.params[1] - 0.25).abs() < 1e-6, "{:?}", r.params);
    assert_eq!(b.at_bounds(&r.params, 1e-6), vec![0]);
}

#[test]
fn an_iteration_cap_is_reported_as_such() {
    // Two iterations from (-1.2, 1) cannot reach Rosenbrock's minimum: the result says
    // MaxIterations, never a tolerance it did not meet.
    let b = Bounds::new(vec!["x".into(), "y".into()], vec![-2.0, -1.0], vec![2.0, 3.0]).unwrap();
    let capped = LmOptions { max_iterations: 2, ..LmOptions::precise() };
    let r = minimise(&Rosen, &b, &DVector::from_vec(vec![-1.2, 1.0]), &capped).unwrap();
    assert_eq!(r.termination, Termination::MaxIterations);
    assert_eq!(r.iterations, 2);
    let r = minimise(&Rosen, &b, &DVector::from_vec(vec![-1.2, 1.0]), &LmOptions::precise()).unwrap();
    assert_ne!(r.termination, Termination::MaxIterations);
}

#[test]
fn cholesky_solves_a_spd_system_and_rejects_an_indefinite_one() {
    // A = [[4, 2, 0], [2, 5, 1], [0, 1, 3]], x = (1, -1, 2): b = A x = (2, -1, 5) (by hand).
    let mut a = vec![4.0, 2.0, 0.0, 2.0, 5.0, 1.0, 0.0, 1.0, 3.0];
    let mut b = vec![2.0, -1.0, 5.0];
    assert!(cholesky_solve(&mut a, &mut b));
    for (x, want) in b.iter().zip([1.0, -1.0, 2.0]) {
        assert!((x - want).abs() < 1e-14, "{b:?}");
    }
    let mut a = vec![1.0, 2.0, 2.0, 1.0];
    assert!(!cholesky_solve(&mut a, &mut [1.0, 1.0]));
}

#[test]
fn rejects_inverted_bounds() {
    assert!(Bounds::new(vec!["x".into()], vec![1.0], vec![0.0]).is_err());
    assert!(Bounds::new(vec!["x".into()], vec![f64::NAN], vec![0.0]).is_err());
}

/// Rosenbrock with forward differences taken from the residuals the minimiser hands over; it
/// counts the calls and the hand-overs that differ from a fresh evaluation at the same point.
struct HandOver {
    calls: std::cell::Cell<usize>,
    stale: std::cell::Cell<usize>,
}
impl Problem for HandOver {
    fn parameter_count(&self) -> usize {
        2
    }
    fn residual_count(&self) -> usize {
        2
    }
    fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
        Rosen.residuals(p, out)
    }
    fn jacobian_at(
        &self,
        p: &DVector<f64>,
        r: &DVector<f64>,
        _b: &Bounds,
        out: &mut DMatrix<f64>,
    ) -> Result<(), IdentError> {
        let mut fresh = DVector::zeros(2);
        self.residuals(p, &mut fresh)?;
        self.calls.set(self.calls.get() + 1);
        if fresh.iter().zip(r.iter()).any(|(a, b)| a.to_bits() != b.to_bits()) {
            self.stale.set(self.stale.get() + 1);
        }
        let mut q = p.clone();
        let mut rq = DVector::zeros(2);
        for k in 0..2 {
            q[k] = p[k] + 1e-7;
            self.residuals(&q, &mut rq)?;
            q[k] = p[k];
            for i in 0..2 {
                out[(i, k)] = (rq[i] - r[i]) / 1e-7;
            }
        }
        Ok(())
    }
}

#[test]
fn the_minimiser_hands_over_the_residuals_at_the_jacobian_s_own_point() {
    // `jacobian_at` may take `r` as its base point only if it is exactly r(p): after the start,
    // after accepted steps and after rejected ones (which leave p and r as they were).
    let b = Bounds::new(vec!["x".into(), "y".into()], vec![-2.0, -1.0], vec![2.0, 3.0]).unwrap();
    let pr = HandOver { calls: 0.into(), stale: 0.into() };
    let r = minimise(&pr, &b, &DVector::from_vec(vec![-1.2, 1.0]), &LmOptions::precise()).unwrap();
    assert!((r.params[0] - 1.0).abs() < 1e-6 && (r.params[1] - 1.0).abs() < 1e-6, "{:?}", r.params);
    assert!(pr.calls.get() > 5, "{} Jacobians", pr.calls.get());
    assert_eq!(pr.stale.get(), 0);
}
