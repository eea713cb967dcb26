//! Numbers formatted for people, in messages and logs.

/// A number formatted for people, in messages and logs: three significant digits by default (the
/// formatter's precision if given, `{:.6}`), trailing zeros dropped, plain decimals for
/// `0.01 ≤ |x| < 10⁴` and `2.63e-3` outside, `0` for zero, `NaN` and `inf` as such. `{:e}` prints
/// `0e0` and `2.626396615835748e-1`; `{}` prints every digit of a computed value.
///
/// ```
/// use tribo::Num;
/// assert_eq!(Num(2.626396615835748e-3).to_string(), "2.63e-3");
/// assert_eq!(Num(0.0).to_string(), "0");
/// assert_eq!(format!("{:.5}", Num(0.1 + 0.2)), "0.3");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() {
            return write!(f, "{}", if x == 0.0 { 0.0 } else { x });
        }
        let digits = f.precision().unwrap_or(3).clamp(1, 17);
        // The exponent after rounding to `digits` (9.996e-3 is 1.00e-2).
        let sci = format!("{:.*e}", digits - 1, x);
        let (mantissa, exponent) = sci.split_once('e').unwrap_or((&sci, "0"));
        let exponent: i32 = exponent.parse().unwrap_or(0);
        let trim = |s: &str| -> String {
            if s.contains('.') {
                s.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                s.to_string()
            }
        };
        if (-2..4).contains(&exponent) {
            let decimals = usize::try_from(digits as i32 - 1 - exponent).unwrap_or(0);
            f.write_str(&trim(&format!("{x:.decimals$}")))
        } else {
            write!(f, "{}e{exponent}", trim(mantissa))
        }
    }
}
