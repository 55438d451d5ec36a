#![allow(dead_code)]
//! Double-double arithmetic (about 32 significant digits) for the tests'
//! independent checks: a value is an unevaluated sum `hi + lo` of two f64
//! with `|lo| ≤ ulp(hi)/2`. Error-free transformations after Knuth
//! (two-sum) and Dekker (two-product, here through a fused multiply–add);
//! the operations as in Bailey's QD library (Hida, Li & Bailey 2001).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// `hi + lo`, exactly.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Dd {
    pub hi: f64,
    pub lo: f64,
}

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

impl Dd {
    pub fn new(x: f64) -> Self {
        Self { hi: x, lo: 0.0 }
    }

    /// The nearest f64.
    pub fn f64(self) -> f64 {
        self.hi + self.lo
    }

    pub fn abs(self) -> Self {
        if self.hi < 0.0 { -self } else { self }
    }

    /// Square root: one Newton step from the f64 root (Karp's trick).
    pub fn sqrt(self) -> Self {
        if self.hi <= 0.0 {
            return Self::new(0.0);
        }
        let x = self.hi.sqrt();
        let (p, e) = two_prod(x, x);
        let r = ((self.hi - p) - e + self.lo) / (2.0 * x);
        let (hi, lo) = quick_two_sum(x, r);
        Self { hi, lo }
    }
}

impl From<f64> for Dd {
    fn from(x: f64) -> Self {
        Self::new(x)
    }
}

impl Add for Dd {
    type Output = Dd;
    fn add(self, b: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, b.hi);
        let (t, f) = two_sum(self.lo, b.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        Dd { hi, lo }
    }
}

impl Neg for Dd {
    type Output = Dd;
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for Dd {
    type Output = Dd;
    fn sub(self, b: Dd) -> Dd {
        self + (-b)
    }
}

impl Mul for Dd {
    type Output = Dd;
    fn mul(self, b: Dd) -> Dd {
        let (p, e) = two_prod(self.hi, b.hi);
        let e = e + (self.hi * b.lo + self.lo * b.hi);
        let (hi, lo) = quick_two_sum(p, e);
        Dd { hi, lo }
    }
}

impl Div for Dd {
    type Output = Dd;
    fn div(self, b: Dd) -> Dd {
        let q1 = self.hi / b.hi;
        let r = self - b * Dd::new(q1);
        let q2 = r.hi / b.hi;
        let r = r - b * Dd::new(q2);
        let q3 = r.hi / b.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        Dd { hi, lo } + Dd::new(q3)
    }
}

/// A 3-vector of double-doubles.
#[derive(Clone, Copy, Debug)]
pub struct Dd3(pub [Dd; 3]);

impl Dd3 {
    pub fn of(x: glam::DVec3) -> Self {
        Self([x.x.into(), x.y.into(), x.z.into()])
    }

    pub fn dot(self, b: Dd3) -> Dd {
        self.0[0] * b.0[0] + self.0[1] * b.0[1] + self.0[2] * b.0[2]
    }

    pub fn length(self) -> Dd {
        self.dot(self).sqrt()
    }

    pub fn scale(self, k: Dd) -> Dd3 {
        Dd3(self.0.map(|x| x * k))
    }
}

impl Add for Dd3 {
    type Output = Dd3;
    fn add(self, b: Dd3) -> Dd3 {
        Dd3([self.0[0] + b.0[0], self.0[1] + b.0[1], self.0[2] + b.0[2]])
    }
}

impl Sub for Dd3 {
    type Output = Dd3;
    fn sub(self, b: Dd3) -> Dd3 {
        Dd3([self.0[0] - b.0[0], self.0[1] - b.0[1], self.0[2] - b.0[2]])
    }
}
