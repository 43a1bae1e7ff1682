//! Temperature polynomials: the fitted property laws of the paper's Table 3.
//!
//! A [`TempPolynomial`] maps a temperature in degC to a property value in SI units
//! (the unit conversion from the paper's units happens where the fixture is read).

use serde::{Deserialize, Serialize};

use crate::error::{check_finite, ModelError};

/// A polynomial `p(T) = c0 + c1 T + c2 T^2 + ...` with `T` in degC and the value in SI units.
///
/// **Source:** the fitted equations of Table 3 (paper), scaled to SI at the edge.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TempPolynomial {
    coefficients: Vec<f64>,
}

impl TempPolynomial {
    /// Builds a polynomial from ascending coefficients (constant first).
    ///
    /// Returns an error if there are no coefficients or one is not finite.
    ///
    /// # Example
    /// ```
    /// use cutcal_model::TempPolynomial;
    /// let p = TempPolynomial::new(vec![1.0, 2.0]).unwrap();
    /// assert!((p.value(3.0) - 7.0).abs() < 1e-12);
    /// ```
    pub fn new(coefficients: Vec<f64>) -> Result<Self, ModelError> {
        if coefficients.is_empty() {
            return Err(ModelError::Inconsistent("a polynomial needs at least one coefficient".into()));
        }
        for (i, c) in coefficients.iter().enumerate() {
            check_finite(&format!("coefficient[{i}]"), *c)?;
        }
        Ok(Self { coefficients })
    }

    /// A constant polynomial.
    #[must_use]
    pub fn constant(value: f64) -> Self {
        Self { coefficients: vec![value] }
    }

    /// The ascending coefficients.
    #[must_use]
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// Every coefficient multiplied by `factor` (a unit conversion).
    #[must_use]
    pub fn scaled(&self, factor: f64) -> Self {
        Self { coefficients: self.coefficients.iter().map(|c| c * factor).collect() }
    }

    /// The product of two polynomials (e.g. `rho(T) * Cp(T)`).
    #[must_use]
    pub fn product(&self, other: &Self) -> Self {
        let mut c = vec![0.0; self.coefficients.len() + other.coefficients.len() - 1];
        for (i, a) in self.coefficients.iter().enumerate() {
            for (j, b) in other.coefficients.iter().enumerate() {
                c[i + j] += a * b;
            }
        }
        Self { coefficients: c }
    }

    /// Value at `temperature_c` (Horner).
    #[must_use]
    pub fn value(&self, temperature_c: f64) -> f64 {
        self.coefficients.iter().rev().fold(0.0, |acc, c| acc * temperature_c + c)
    }

    /// First derivative with respect to temperature at `temperature_c`.
    #[must_use]
    pub fn derivative(&self, temperature_c: f64) -> f64 {
        self.coefficients.iter().enumerate().skip(1).rev().fold(0.0, |acc, (i, c)| acc * temperature_c + c * i as f64)
    }

    /// The antiderivative `P(T) = sum c_i T^(i+1)/(i+1)`, zero at 0 degC.
    #[must_use]
    pub fn antiderivative(&self, temperature_c: f64) -> f64 {
        self.coefficients.iter().enumerate().rev().fold(0.0, |acc, (i, c)| acc * temperature_c + c / (i as f64 + 1.0))
            * temperature_c
    }

    /// The antiderivative as a polynomial (zero at 0 degC): coefficients `c_i / (i + 1)` shifted up
    /// one degree, so that repeated evaluations need no division.
    #[must_use]
    pub fn antiderivative_polynomial(&self) -> Self {
        let mut c = Vec::with_capacity(self.coefficients.len() + 1);
        c.push(0.0);
        c.extend(self.coefficients.iter().enumerate().map(|(i, a)| a / (i as f64 + 1.0)));
        Self { coefficients: c }
    }

    /// The exact integral of the polynomial from `from_c` to `to_c`.
    #[must_use]
    pub fn integral(&self, from_c: f64, to_c: f64) -> f64 {
        self.antiderivative(to_c) - self.antiderivative(from_c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivative_and_integral_match_hand_calculation() {
        // p(T) = 1 + 2T + 3T^2: p' = 2 + 6T, P(T) = T + T^2 + T^3.
        let p = TempPolynomial::new(vec![1.0, 2.0, 3.0]).unwrap();
        assert!((p.value(2.0) - 17.0).abs() < 1e-12);
        assert!((p.derivative(2.0) - 14.0).abs() < 1e-12);
        assert!((p.integral(1.0, 2.0) - (14.0 - 3.0)).abs() < 1e-12);
        // The antiderivative polynomial is T + T^2 + T^3.
        assert_eq!(p.antiderivative_polynomial().coefficients(), &[0.0, 1.0, 1.0, 1.0]);
    }

    #[test]
    fn product_multiplies_values() {
        let a = TempPolynomial::new(vec![7.866, -8.465e-4]).unwrap();
        let b = TempPolynomial::new(vec![0.2306, 0.0025, -3.653e-6]).unwrap();
        let p = a.product(&b);
        for t in [0.0, 20.0, 500.0, 1200.0] {
            assert!((p.value(t) - a.value(t) * b.value(t)).abs() < 1e-9);
        }
    }

    #[test]
    fn rejects_nan_coefficient() {
        assert!(TempPolynomial::new(vec![1.0, f64::NAN]).is_err());
        assert!(TempPolynomial::new(vec![]).is_err());
    }
}
