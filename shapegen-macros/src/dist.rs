//! Checking a parameter's distribution against its type: the distribution applies to the
//! type, takes the right arguments, and its bounds, ranges, weights or probability are
//! valid; every mistake reported on the user's tokens.

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;
use syn::Expr;

use crate::consteval::{eval_f32, eval_f64, eval_int, eval_vec, peel, to_f32};
use crate::ctxt::Ctxt;
use crate::model::{AngleUnit, Dist, ParamType};
use crate::parse;

/// Tokens whose first and last spans are `start` and `end`, so that an error spanned on
/// them covers everything in between.
fn span_range(start: Span, end: Span) -> TokenStream {
    let a = Ident::new("a", start);
    let b = Ident::new("b", end);
    quote!(#a #b)
}

/// The distributions each type takes, for messages.
fn dists_of(ty: ParamType) -> &'static str {
    match ty {
        ParamType::F32 => "`uniform(lo, hi)`, `degrees(lo, hi)` or `radians(lo, hi)`",
        ParamType::Vec2 => "`uniform([x, y], [x, y])` (or `[v; 2]` bounds)",
        ParamType::Vec3 => "`uniform([x, y, z], [x, y, z])` (or `[v; 3]` bounds)",
        ParamType::I32 => "`uniform(lo..=hi)` or `uniform(lo..hi)`",
        ParamType::U32 => "`uniform(lo..=hi)`, `uniform(lo..hi)` or `weighted([w0, w1, ..])`",
        ParamType::Bool => "`bernoulli(p)`",
    }
}

/// The distribution of parameter `p` of type `ty`, or `None` after reporting in `cx`
/// why it does not fit.
pub fn check_dist(ty: ParamType, p: &parse::Param, cx: &Ctxt) -> Option<Dist> {
    let call = DistCall {
        ty,
        d: p.dist.to_string(),
        tn: ty.name(),
        an: if matches!(ty, ParamType::F32 | ParamType::I32) {
            "an"
        } else {
            "a"
        },
        args: p.args.iter().collect(),
        span: span_range(p.dist.span(), p.paren.span.close()),
        cx,
    };
    let applies = matches!(
        (ty, call.d.as_str()),
        (ParamType::F32, "uniform" | "degrees" | "radians")
            | (
                ParamType::Vec2 | ParamType::Vec3 | ParamType::I32,
                "uniform"
            )
            | (ParamType::U32, "uniform" | "weighted")
            | (ParamType::Bool, "bernoulli")
    );
    if !applies {
        let (d, an, tn) = (&call.d, call.an, call.tn);
        let known =
            ["uniform", "degrees", "radians", "weighted", "bernoulli"].contains(&d.as_str());
        let what = if known {
            format!("`{d}` does not apply to {an} `{tn}` parameter")
        } else {
            format!("unknown distribution `{d}`")
        };
        cx.error(
            &p.dist,
            format_args!("{what}; {an} `{tn}` parameter takes {}", dists_of(ty)),
        );
        return None;
    }
    match (ty, call.d.as_str()) {
        (ParamType::F32, _) => call.float(),
        (ParamType::Vec2 | ParamType::Vec3, _) => call.vector(),
        (ParamType::I32 | ParamType::U32, "uniform") => call.range(),
        (ParamType::U32, _) => {
            if !call.arity(1, "weighted([w0, w1, ..])") {
                return None;
            }
            check_weights(call.args[0], cx).map(|weights| Dist::Weighted { weights })
        }
        (ParamType::Bool, _) => call.bernoulli(),
        _ => None,
    }
}

/// One distribution as written, for a parameter of type `ty`.
struct DistCall<'a> {
    ty: ParamType,
    /// The distribution's name.
    d: String,
    /// The type's name, and its article.
    tn: &'static str,
    an: &'static str,
    args: Vec<&'a Expr>,
    /// The whole call, for errors about its arguments.
    span: TokenStream,
    cx: &'a Ctxt,
}

impl DistCall<'_> {
    /// Whether the call has `n` arguments; reports the written `form` otherwise.
    fn arity(&self, n: usize, form: &str) -> bool {
        if self.args.len() == n {
            return true;
        }
        self.cx.error(
            &self.span,
            format_args!(
                "`{}` for {} `{}` parameter takes {} argument{}: `{form}`",
                self.d,
                self.an,
                self.tn,
                n,
                if n == 1 { "" } else { "s" },
            ),
        );
        false
    }

    /// `uniform`, `degrees` or `radians` of an `f32`: two bounds, lower first.
    fn float(&self) -> Option<Dist> {
        let (d, args, cx) = (&self.d, &self.args, self.cx);
        if !self.arity(2, &format!("{d}(lo, hi)")) {
            return None;
        }
        let lo = eval_f64(args[0]).map_err(|e| cx.push(e));
        let hi = eval_f64(args[1]).map_err(|e| cx.push(e));
        let (lo, hi) = (lo.ok()?, hi.ok()?);
        if lo > hi {
            cx.error(
                quote!(#(#args),*),
                format_args!(
                    "empty range: the lower bound {lo:?} is greater than the upper bound \
                     {hi:?}; write `{d}({hi:?}, {lo:?})`"
                ),
            );
            return None;
        }
        let (lo32, hi32) = match d.as_str() {
            "degrees" => (lo.to_radians(), hi.to_radians()),
            _ => (lo, hi),
        };
        let lo32 = to_f32(lo32, args[0]).map_err(|e| cx.push(e));
        let hi32 = to_f32(hi32, args[1]).map_err(|e| cx.push(e));
        let (lo32, hi32) = (lo32.ok()?, hi32.ok()?);
        Some(match d.as_str() {
            "uniform" => Dist::Uniform { lo: lo32, hi: hi32 },
            unit => Dist::Angle {
                lo: lo32,
                hi: hi32,
                unit: if unit == "degrees" {
                    AngleUnit::Degrees
                } else {
                    AngleUnit::Radians
                },
                written: (lo, hi),
            },
        })
    }

    /// `uniform` of a `Vec2` or `Vec3`: two arrays of bounds, each component's lower
    /// first.
    fn vector(&self) -> Option<Dist> {
        let (args, cx, an, tn) = (&self.args, self.cx, self.an, self.tn);
        let n = self.ty.words() as usize;
        let form = if n == 2 {
            "uniform([x, y], [x, y])"
        } else {
            "uniform([x, y, z], [x, y, z])"
        };
        if !self.arity(2, form) {
            return None;
        }
        if !args
            .iter()
            .any(|a| matches!(peel(a), Expr::Array(_) | Expr::Repeat(_)))
        {
            cx.error(
                quote!(#(#args),*),
                format_args!(
                    "the bounds of {an} `{tn}` parameter are arrays, one number per \
                     component: `{form}`, or `[v; {n}]` for equal components"
                ),
            );
            return None;
        }
        let lo = eval_vec(args[0], n, tn).map_err(|e| cx.push(e));
        let hi = eval_vec(args[1], n, tn).map_err(|e| cx.push(e));
        let (lo, hi) = (lo.ok()?, hi.ok()?);
        let mut ok = true;
        let mut lo32 = [0.0f32; 3];
        let mut hi32 = [0.0f32; 3];
        // Empty components, grouped by the bounds they were written as, so that
        // `[1.5; 3]` over `[0.6; 3]` is one mistake.
        let mut empty: Vec<(usize, usize, Vec<&str>)> = Vec::new();
        for (i, (l, h)) in lo.iter().zip(&hi).enumerate() {
            let axis = ["x", "y", "z"][i];
            if l.value > h.value {
                ok = false;
                let same = |&(a, b, _): &(usize, usize, Vec<&str>)| {
                    std::ptr::eq(lo[a].expr, l.expr) && std::ptr::eq(hi[b].expr, h.expr)
                };
                match empty.iter_mut().find(|e| same(e)) {
                    Some(e) => e.2.push(axis),
                    None => empty.push((i, i, vec![axis])),
                }
                continue;
            }
            match (to_f32(l.value, l.expr), to_f32(h.value, h.expr)) {
                (Ok(a), Ok(b)) => (lo32[i], hi32[i]) = (a, b),
                (a, b) => {
                    ok = false;
                    a.err().into_iter().chain(b.err()).for_each(|e| cx.push(e));
                }
            }
        }
        for (i, _, axes) in empty {
            let (l, h) = (lo[i].value, hi[i].value);
            let which = match axes.as_slice() {
                [one] => format!("component {one}"),
                many => format!("components {}", many.join(", ")),
            };
            cx.error(
                hi[i].expr,
                format_args!(
                    "empty range in {which}: the upper bound {h:?} is below the lower \
                     bound {l:?}; each component needs lower <= upper"
                ),
            );
        }
        ok.then(|| {
            if n == 2 {
                Dist::UniformVec2 {
                    lo: [lo32[0], lo32[1]],
                    hi: [hi32[0], hi32[1]],
                }
            } else {
                Dist::UniformVec3 { lo: lo32, hi: hi32 }
            }
        })
    }

    /// `uniform` of an `i32` or `u32`: one range, both ends written, not empty, within
    /// the type.
    fn range(&self) -> Option<Dist> {
        let (cx, an, tn) = (self.cx, self.an, self.tn);
        let range = match self.args.as_slice() {
            [arg] => match peel(arg) {
                Expr::Range(r) => Some(r),
                _ => None,
            },
            _ => None,
        };
        let Some(r) = range else {
            cx.error(
                &self.span,
                format_args!(
                    "{an} `{tn}` parameter takes a range: `uniform(lo..=hi)` (both ends \
                     included) or `uniform(lo..hi)`"
                ),
            );
            return None;
        };
        let (Some(start), Some(end)) = (&r.start, &r.end) else {
            cx.error(
                r,
                "the range needs both ends: `uniform(lo..=hi)` or `uniform(lo..hi)`",
            );
            return None;
        };
        let a = eval_int(start).map_err(|e| cx.push(e));
        let b = eval_int(end).map_err(|e| cx.push(e));
        let (a, b) = (a.ok()?, b.ok()?);
        let closed = matches!(r.limits, syn::RangeLimits::Closed(_));
        let (lo, hi) = if closed { (a, b) } else { (a, b - 1) };
        if lo > hi {
            let msg = if closed {
                format!("the range {a}..={b} is empty: {b} is below {a}; write `{b}..={a}`")
            } else if a == b {
                format!(
                    "the range {a}..{b} is empty (`..` leaves out its upper end); write \
                     `{a}..={a}` for the single value {a}"
                )
            } else {
                format!("the range {a}..{b} is empty: it needs {a} < {b}")
            };
            cx.error(r, msg);
            return None;
        }
        self.int_within([lo, hi], [start, end])
    }

    /// The integer range `lo..=hi` (written as `exprs`) as the parameter's distribution,
    /// if both ends fit its type.
    fn int_within(&self, [lo, hi]: [i128; 2], exprs: [&Expr; 2]) -> Option<Dist> {
        let (an, tn) = (self.an, self.tn);
        let (min, max) = if self.ty == ParamType::I32 {
            (i128::from(i32::MIN), i128::from(i32::MAX))
        } else {
            (0, i128::from(u32::MAX))
        };
        let mut ok = true;
        for (v, e) in [(lo, exprs[0]), (hi, exprs[1])] {
            if v < min || v > max {
                ok = false;
                self.cx.error(
                    e,
                    format_args!(
                        "{v} does not fit {an} `{tn}` parameter, whose values lie in \
                         {min}..={max}"
                    ),
                );
            }
        }
        if !ok {
            return None;
        }
        Some(if self.ty == ParamType::I32 {
            Dist::Int {
                lo: lo as i32,
                hi: hi as i32,
            }
        } else {
            Dist::Index {
                lo: lo as u32,
                hi: hi as u32,
            }
        })
    }

    /// `bernoulli` of a `bool`: one probability in `[0, 1]`.
    fn bernoulli(&self) -> Option<Dist> {
        if !self.arity(1, "bernoulli(p)") {
            return None;
        }
        match eval_f32(self.args[0]) {
            Ok(p) if (0.0..=1.0).contains(&p) => Some(Dist::Bernoulli { p }),
            Ok(p) => {
                self.cx.error(
                    self.args[0],
                    format_args!(
                        "probability {p:?} is outside [0, 1]; `bernoulli(p)` is `true` with \
                         probability p, between 0.0 and 1.0"
                    ),
                );
                None
            }
            Err(e) => {
                self.cx.push(e);
                None
            }
        }
    }
}

/// The weights of `weighted`: an array (or `[w; n]`) of at least one weight, none
/// negative, not all zero.
fn check_weights(arg: &Expr, cx: &Ctxt) -> Option<Vec<f32>> {
    let exprs: Vec<&Expr> = match peel(arg) {
        Expr::Array(a) => a.elems.iter().collect(),
        Expr::Repeat(r) => match eval_int(&r.len) {
            Ok(n) if (0..=1 << 16).contains(&n) => vec![&*r.expr; n as usize],
            Ok(n) => {
                cx.error(&r.len, format_args!("{n} weights are too many or too few"));
                return None;
            }
            Err(e) => {
                cx.push(e);
                return None;
            }
        },
        _ => {
            cx.error(
                arg,
                "`weighted` takes an array of weights: `weighted([1.0, 2.0, 0.5])`; index i is \
                 drawn with probability w_i / sum(w)",
            );
            return None;
        }
    };
    if exprs.is_empty() {
        cx.error(
            arg,
            "`weighted` needs at least one weight: `weighted([1.0, 2.0])`",
        );
        return None;
    }
    let mut ok = true;
    let mut weights = Vec::with_capacity(exprs.len());
    for e in &exprs {
        match eval_f32(e) {
            Ok(w) if w < 0.0 => {
                ok = false;
                cx.error(
                    e,
                    format_args!("weight {w:?} is negative; weights are 0 or more"),
                );
            }
            Ok(w) => weights.push(w),
            Err(err) => {
                ok = false;
                cx.push(err);
            }
        }
    }
    if ok && weights.iter().all(|&w| w == 0.0) {
        cx.error(
            arg,
            "every weight is zero; at least one must be positive, or no index can be drawn",
        );
        return None;
    }
    ok.then_some(weights)
}
