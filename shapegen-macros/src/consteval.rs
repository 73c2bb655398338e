//! Constant expressions, evaluated when the macro expands.
//!
//! Bounds, probabilities, weights and array lengths are written as small constant
//! expressions and turned into numbers here, so that the generator graph holds plain
//! literals and every value can be checked with a span on the user's tokens.
//!
//! The language: integer and float literals (any numeric suffix), unary `-`, binary
//! `+ - * /`, parentheses, and the `f32`/`f64` constants by name (`PI`, `TAU`,
//! `FRAC_PI_2`, ...), bare or as `std::f32::consts::PI`, `core::f32::consts::PI`,
//! `f32::consts::PI` (or `f64`). Vector bounds are `[x; N]` or `[a, b, c]`.
//!
//! Float positions evaluate in `f64` (integer literals are read as floats there, so
//! `1 / 3` is a third) and round to the nearest `f32` at the end; integer positions
//! evaluate in `i128` with Rust's truncating division and reject float literals.

use syn::{BinOp, Error, Expr, Lit, Result, UnOp};

/// What the language allows, for error messages.
const LANGUAGE: &str = "number literals, unary `-`, `+ - * /`, parentheses and the f32 \
     constants such as `PI`, `TAU` or `FRAC_PI_2`";

/// The named constants, with their `f64` values.
const CONSTS: &[(&str, f64)] = {
    use std::f64::consts as c;
    &[
        ("PI", c::PI),
        ("TAU", c::TAU),
        ("E", c::E),
        ("FRAC_PI_2", c::FRAC_PI_2),
        ("FRAC_PI_3", c::FRAC_PI_3),
        ("FRAC_PI_4", c::FRAC_PI_4),
        ("FRAC_PI_6", c::FRAC_PI_6),
        ("FRAC_PI_8", c::FRAC_PI_8),
        ("FRAC_1_PI", c::FRAC_1_PI),
        ("FRAC_2_PI", c::FRAC_2_PI),
        ("FRAC_2_SQRT_PI", c::FRAC_2_SQRT_PI),
        ("SQRT_2", c::SQRT_2),
        ("FRAC_1_SQRT_2", c::FRAC_1_SQRT_2),
        ("LN_2", c::LN_2),
        ("LN_10", c::LN_10),
        ("LOG2_E", c::LOG2_E),
        ("LOG10_E", c::LOG10_E),
        ("LOG2_10", c::LOG2_10),
        ("LOG10_2", c::LOG10_2),
    ]
};

/// One component of a vector bound, with the expression it came from (for spans).
#[derive(Clone, Copy, Debug)]
pub struct Component<'a> {
    /// The value, not yet rounded to `f32`.
    pub value: f64,
    /// The expression the value was written as.
    pub expr: &'a Expr,
}

/// Strips parentheses and invisible groups.
pub fn peel(mut expr: &Expr) -> &Expr {
    loop {
        match expr {
            Expr::Paren(p) => expr = &p.expr,
            Expr::Group(g) => expr = &g.expr,
            _ => return expr,
        }
    }
}

fn not_constant(expr: &Expr) -> Error {
    let written = match expr {
        Expr::Path(p) => {
            let segs: Vec<String> = p
                .path
                .segments
                .iter()
                .map(|s| s.ident.to_string())
                .collect();
            format!("`{}`", segs.join("::"))
        }
        _ => "this expression".to_owned(),
    };
    Error::new_spanned(
        expr,
        format!(
            "the macro cannot evaluate {written}: bounds, probabilities and lengths are \
             evaluated when the macro expands, from {LANGUAGE} only; write the value instead"
        ),
    )
}

/// Evaluates `expr` in a float position; the result is finite.
pub fn eval_f64(expr: &Expr) -> Result<f64> {
    let v = float(expr)?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::new_spanned(
            expr,
            format!("this constant evaluates to {v}, not a finite number (a division by zero?)"),
        ))
    }
}

/// Evaluates `expr` in a float position and rounds it to the nearest `f32`, which must be
/// finite.
pub fn eval_f32(expr: &Expr) -> Result<f32> {
    to_f32(eval_f64(expr)?, expr)
}

/// Rounds `v`, written as `expr`, to the nearest `f32`.
pub fn to_f32(v: f64, expr: &Expr) -> Result<f32> {
    let r = v as f32;
    if r.is_finite() {
        Ok(r)
    } else {
        Err(Error::new_spanned(
            expr,
            format!(
                "{v} is too large for an f32; f32 values lie within ±{}",
                f32::MAX
            ),
        ))
    }
}

fn float(expr: &Expr) -> Result<f64> {
    match peel(expr) {
        Expr::Lit(lit) => match &lit.lit {
            Lit::Float(f) => {
                check_suffix(f.suffix(), lit)?;
                f.base10_parse::<f64>()
            }
            Lit::Int(i) => {
                check_suffix(i.suffix(), lit)?;
                i.base10_parse::<f64>()
            }
            _ => Err(Error::new_spanned(
                lit,
                format!(
                    "expected a number, found this literal; constants are written with {LANGUAGE}"
                ),
            )),
        },
        Expr::Unary(u) => match u.op {
            UnOp::Neg(_) => Ok(-float(&u.expr)?),
            _ => Err(Error::new_spanned(
                u.op,
                format!(
                    "this operator is not supported in constants, which are written with {LANGUAGE}"
                ),
            )),
        },
        Expr::Binary(b) => {
            let (l, r) = (float(&b.left)?, float(&b.right)?);
            match b.op {
                BinOp::Add(_) => Ok(l + r),
                BinOp::Sub(_) => Ok(l - r),
                BinOp::Mul(_) => Ok(l * r),
                BinOp::Div(_) => Ok(l / r),
                _ => Err(unsupported_op(&b.op)),
            }
        }
        Expr::Path(p) => named_const(p).ok_or_else(|| not_constant(expr)),
        Expr::Array(_) | Expr::Repeat(_) => Err(Error::new_spanned(
            expr,
            "expected a number here, found an array; arrays are only bounds of `Vec2` and \
             `Vec3` parameters and the weights of `weighted`",
        )),
        other => Err(not_constant(other)),
    }
}

/// Evaluates `expr` in an integer position.
pub fn eval_int(expr: &Expr) -> Result<i128> {
    let overflow = || Error::new_spanned(expr, "this integer constant overflows");
    match peel(expr) {
        Expr::Lit(lit) => match &lit.lit {
            Lit::Int(i) => {
                check_suffix(i.suffix(), lit)?;
                i.base10_parse::<i128>()
            }
            Lit::Float(_) => Err(Error::new_spanned(
                lit,
                "expected an integer here, found a float; write it without a decimal point",
            )),
            _ => Err(Error::new_spanned(
                lit,
                format!(
                    "expected an integer, found this literal; constants are written with {LANGUAGE}"
                ),
            )),
        },
        Expr::Unary(u) => match u.op {
            UnOp::Neg(_) => eval_int(&u.expr)?.checked_neg().ok_or_else(overflow),
            _ => Err(Error::new_spanned(
                u.op,
                format!(
                    "this operator is not supported in constants, which are written with {LANGUAGE}"
                ),
            )),
        },
        Expr::Binary(b) => {
            let (l, r) = (eval_int(&b.left)?, eval_int(&b.right)?);
            match b.op {
                BinOp::Add(_) => l.checked_add(r).ok_or_else(overflow),
                BinOp::Sub(_) => l.checked_sub(r).ok_or_else(overflow),
                BinOp::Mul(_) => l.checked_mul(r).ok_or_else(overflow),
                BinOp::Div(_) if r == 0 => Err(Error::new_spanned(expr, "division by zero")),
                BinOp::Div(_) => l.checked_div(r).ok_or_else(overflow),
                _ => Err(unsupported_op(&b.op)),
            }
        }
        Expr::Path(p) if named_const(p).is_some() => Err(Error::new_spanned(
            expr,
            "expected an integer here, found a float constant",
        )),
        other => Err(not_constant(other)),
    }
}

fn unsupported_op(op: &BinOp) -> Error {
    Error::new_spanned(
        op,
        format!("this operator is not supported in constants, which are written with {LANGUAGE}"),
    )
}

fn check_suffix(suffix: &str, lit: &syn::ExprLit) -> Result<()> {
    const OK: &[&str] = &[
        "", "f32", "f64", "i8", "i16", "i32", "i64", "i128", "isize", "u8", "u16", "u32", "u64",
        "u128", "usize",
    ];
    if OK.contains(&suffix) {
        Ok(())
    } else {
        Err(Error::new_spanned(
            lit,
            format!(
                "unknown literal suffix `{suffix}`; use a numeric suffix such as `f32` or none"
            ),
        ))
    }
}

/// The value of a named constant path such as `PI` or `std::f32::consts::PI`.
fn named_const(p: &syn::ExprPath) -> Option<f64> {
    if p.qself.is_some() || p.path.segments.iter().any(|s| !s.arguments.is_none()) {
        return None;
    }
    let segs: Vec<String> = p
        .path
        .segments
        .iter()
        .map(|s| s.ident.to_string())
        .collect();
    let (name, prefix) = segs.split_last()?;
    let prefix: Vec<&str> = prefix.iter().map(String::as_str).collect();
    let ok_prefix = match prefix.as_slice() {
        [] | ["f32" | "f64", "consts"] => p.path.leading_colon.is_none(),
        ["std" | "core", "f32" | "f64", "consts"] => true,
        _ => false,
    };
    if !ok_prefix {
        return None;
    }
    CONSTS.iter().find(|(n, _)| n == name).map(|&(_, v)| v)
}

/// Evaluates a vector bound of `n` components: `[x; n]` or `[a, b, ..]`. `what` names the
/// parameter type for messages (`"Vec3"`).
pub fn eval_vec<'a>(expr: &'a Expr, n: usize, what: &str) -> Result<Vec<Component<'a>>> {
    match peel(expr) {
        Expr::Array(a) => {
            if a.elems.len() != n {
                return Err(Error::new_spanned(
                    expr,
                    format!(
                        "a {what} bound has {n} components, found {}; write `[{}]` or `[x; {n}]`",
                        a.elems.len(),
                        component_names(n)
                    ),
                ));
            }
            let mut out = Vec::with_capacity(n);
            for e in &a.elems {
                out.push(Component {
                    value: eval_f64(e)?,
                    expr: e,
                });
            }
            Ok(out)
        }
        Expr::Repeat(r) => {
            let len = eval_int(&r.len)?;
            if len != n as i128 {
                return Err(Error::new_spanned(
                    &r.len,
                    format!("a {what} bound has {n} components, found {len}; write `[x; {n}]`"),
                ));
            }
            let value = eval_f64(&r.expr)?;
            Ok(vec![
                Component {
                    value,
                    expr: &r.expr,
                };
                n
            ])
        }
        _ => Err(Error::new_spanned(
            expr,
            format!(
                "a {what} bound is an array: write `[{}]` or `[x; {n}]`",
                component_names(n)
            ),
        )),
    }
}

fn component_names(n: usize) -> &'static str {
    ["", "x", "x, y", "x, y, z"][n.min(3)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use syn::parse_quote;

    fn f(e: Expr) -> Result<f64> {
        eval_f64(&e)
    }

    fn i(e: Expr) -> Result<i128> {
        eval_int(&e)
    }

    #[test]
    fn floats() {
        assert_eq!(f(parse_quote!(1.5)).unwrap(), 1.5);
        assert_eq!(f(parse_quote!(-0.5f32)).unwrap(), -0.5);
        assert_eq!(f(parse_quote!(1 / 3)).unwrap(), 1.0 / 3.0);
        assert_eq!(f(parse_quote!((1.0 + 2.0) * 3.0 - -1.0)).unwrap(), 10.0);
        assert_eq!(f(parse_quote!(PI)).unwrap(), std::f64::consts::PI);
        assert_eq!(
            f(parse_quote!(std::f32::consts::FRAC_PI_2)).unwrap(),
            std::f64::consts::FRAC_PI_2
        );
        assert_eq!(
            f(parse_quote!(::core::f32::consts::TAU / 2.0)).unwrap(),
            std::f64::consts::PI
        );
        assert_eq!(
            f(parse_quote!(f64::consts::E)).unwrap(),
            std::f64::consts::E
        );
        assert_eq!(f(parse_quote!(1e3)).unwrap(), 1000.0);
    }

    #[test]
    fn thirds_round_once_to_the_nearest_f32() {
        let v = eval_f32(&parse_quote!(1.0 / 3.0)).unwrap();
        assert_eq!(v, 1.0f32 / 3.0f32);
        assert_eq!(eval_f32(&parse_quote!(PI)).unwrap(), std::f32::consts::PI);
    }

    #[test]
    fn non_constants_are_rejected() {
        for e in [
            parse_quote!(x),
            parse_quote!(foo::PI),
            parse_quote!(::PI),
            parse_quote!(f(1.0)),
            parse_quote!(1.0 % 2.0),
            parse_quote!(!1.0),
            parse_quote!("a"),
            parse_quote!(1.0 / 0.0),
            parse_quote!([1.0; 3]),
            parse_quote!(1.0abc),
        ] {
            assert!(f(e).is_err());
        }
        assert!(eval_f32(&parse_quote!(1e39)).is_err());
    }

    #[test]
    fn integers() {
        assert_eq!(i(parse_quote!(7 / 2)).unwrap(), 3);
        assert_eq!(i(parse_quote!(-(2 + 3) * 4u32)).unwrap(), -20);
        assert!(i(parse_quote!(1.0)).is_err());
        assert!(i(parse_quote!(PI)).is_err());
        assert!(i(parse_quote!(1 / 0)).is_err());
        assert!(i(parse_quote!(170141183460469231731687303715884105727 + 1)).is_err());
    }

    #[test]
    fn vectors() {
        let e: Expr = parse_quote!([0.5; 3]);
        let v = eval_vec(&e, 3, "Vec3").unwrap();
        assert_eq!(v.iter().map(|c| c.value).collect::<Vec<_>>(), [0.5; 3]);
        let e: Expr = parse_quote!([1, 2.0 / 4.0]);
        let v = eval_vec(&e, 2, "Vec2").unwrap();
        assert_eq!(v.iter().map(|c| c.value).collect::<Vec<_>>(), [1.0, 0.5]);
        for e in [
            parse_quote!([1.0; 2]),
            parse_quote!([1.0, 2.0]),
            parse_quote!(1.0),
            parse_quote!([x, 1.0, 2.0]),
        ] {
            let e: Expr = e;
            assert!(eval_vec(&e, 3, "Vec3").is_err());
        }
    }
}
