//! The LP writer.

use super::names::{assign, Names};
use super::{WriteOptions, NEGATED_MAX_COMMENT, RANGED_ROW_COMMENT};
use crate::io::NameMap;
use crate::milp::{Model, RowKind, Sense, VarKind};
use std::io::{self, Write};

/// Buffered output with line-length tracking.
struct Out<'w, W: Write> {
    w: &'w mut W,
    buf: Vec<u8>,
    /// Bytes since the last newline.
    line_len: usize,
    max: usize,
    ryu: ryu::Buffer,
}

const FLUSH_AT: usize = 1 << 17;

impl<'w, W: Write> Out<'w, W> {
    fn new(w: &'w mut W, max: usize) -> Self {
        Out { w, buf: Vec::with_capacity(FLUSH_AT + 1024), line_len: 0, max, ryu: ryu::Buffer::new() }
    }

    #[inline]
    fn push(&mut self, s: &[u8]) {
        self.buf.extend_from_slice(s);
        self.line_len += s.len();
    }

    /// Ends the line (and flushes the buffer when it is full).
    #[inline]
    fn newline(&mut self) -> io::Result<()> {
        self.buf.push(b'\n');
        self.line_len = 0;
        if self.buf.len() >= FLUSH_AT {
            self.w.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    /// A whole line.
    fn line(&mut self, s: &str) -> io::Result<()> {
        self.push(s.as_bytes());
        self.newline()
    }

    /// Starts a new (continuation) line if a piece of `len` bytes would not fit. Pieces start
    /// with a space, so a continuation line starts with a space.
    #[inline]
    fn room(&mut self, len: usize) -> io::Result<()> {
        if self.line_len > 0 && self.line_len + len > self.max {
            self.newline()?;
        }
        Ok(())
    }

    fn finish(mut self) -> io::Result<()> {
        self.w.write_all(&self.buf)?;
        self.buf.clear();
        Ok(())
    }
}

/// The shortest text of a finite, non-negative `v` that reads back to the same `f64`.
#[inline]
fn fmt_abs<'b>(v: f64, ryu: &'b mut ryu::Buffer, int: &'b mut [u8; 24]) -> &'b [u8] {
    debug_assert!(v.is_finite());
    if v < 1e15 && v == v.trunc() {
        // Integers: faster than ryu.
        let mut n = v as u64;
        let mut i = int.len();
        loop {
            i -= 1;
            int[i] = b'0' + (n % 10) as u8;
            n /= 10;
            if n == 0 {
                break;
            }
        }
        return &int[i..];
    }
    let s = ryu.format_finite(v).as_bytes();
    s.strip_suffix(b".0").unwrap_or(s)
}

/// A finite `v` (with its sign, `-0` for negative zero) or `inf`/`-inf`.
fn fmt_signed(v: f64, ryu: &mut ryu::Buffer) -> String {
    if v.is_infinite() {
        return if v > 0.0 { "+inf".into() } else { "-inf".into() };
    }
    let mut int = [0u8; 24];
    let body = fmt_abs(v.abs(), ryu, &mut int);
    let body = std::str::from_utf8(body).unwrap_or("0");
    if v.is_sign_negative() {
        format!("-{body}")
    } else {
        body.to_string()
    }
}

/// Writes one term: ` + 3 x`, ` - x` (or, first in its expression, ` 3 x`, ` - x`).
#[inline]
fn term<W: Write>(o: &mut Out<W>, first: bool, coef: f64, name: &str) -> io::Result<()> {
    let neg = coef.is_sign_negative();
    let a = coef.abs();
    let mut int = [0u8; 24];
    let mut ryu = std::mem::take(&mut o.ryu);
    let num: &[u8] = if a == 1.0 { b"" } else { fmt_abs(a, &mut ryu, &mut int) };
    let sign: &[u8] = match (first, neg) {
        (_, true) => b" -",
        (false, false) => b" +",
        (true, false) => b"",
    };
    let len = sign.len() + if num.is_empty() { 0 } else { num.len() + 1 } + 1 + name.len();
    o.room(len)?;
    o.push(sign);
    if !num.is_empty() {
        o.buf.push(b' ');
        o.push(num);
    }
    o.buf.push(b' ');
    o.push(name.as_bytes());
    o.line_len += if num.is_empty() { 1 } else { 2 };
    o.ryu = ryu;
    Ok(())
}

/// Why a model cannot be written, if it cannot.
fn unwritable(model: &Model) -> Option<String> {
    for v in model.vars() {
        if v.lb.is_nan() || v.ub.is_nan() || v.obj.is_nan() {
            return Some(format!("variable `{}` has a NaN bound or objective coefficient", v.name));
        }
        if v.obj.is_infinite() {
            return Some(format!("variable `{}` has an infinite objective coefficient", v.name));
        }
        if v.lb == f64::INFINITY || v.ub == f64::NEG_INFINITY {
            return Some(format!("variable `{}` has a bound on the wrong side of infinity", v.name));
        }
    }
    if !model.obj_constant.is_finite() {
        return Some("the objective constant is not finite".into());
    }
    for r in model.rows() {
        if r.lhs.is_nan() || r.rhs.is_nan() || r.lhs == f64::INFINITY || r.rhs == f64::NEG_INFINITY {
            return Some(format!("row `{}` has a NaN side or a side on the wrong side of infinity", r.name));
        }
        if r.coefs.iter().any(|a| !a.is_finite()) {
            return Some(format!("row `{}` has a NaN or infinite coefficient", r.name));
        }
        if r.vars.iter().any(|v| v.index() >= model.num_vars()) {
            return Some(format!("row `{}` refers to an unknown variable", r.name));
        }
    }
    None
}

/// Whether row `lhs..rhs` is written as two rows.
fn is_ranged(lhs: f64, rhs: f64) -> bool {
    lhs.is_finite() && rhs.is_finite() && lhs != rhs
}

pub(super) fn write<W: Write>(model: &Model, w: &mut W, opts: &WriteOptions) -> io::Result<NameMap> {
    if let Some(why) = unwritable(model) {
        return Err(io::Error::new(io::ErrorKind::InvalidInput, format!("model cannot be written as LP: {why}")));
    }
    let (lhs, rhs) = model.row_sides();
    let Names { vars: names, rows: row_names, objective, range_upper, map } =
        assign(model, opts.max_name_len, |i| is_ranged(lhs[i], rhs[i]));
    let mut o = Out::new(w, opts.max_line_len.max(1));

    // Header.
    o.line(concat!("\\ Written by netspec ", env!("CARGO_PKG_VERSION"), " (CPLEX LP format)"))?;
    if !model.name.is_empty() {
        let mut name: String = model.name.chars().map(|c| if c.is_control() { ' ' } else { c }).collect();
        let mut cut = name.len().min(235);
        while !name.is_char_boundary(cut) {
            cut -= 1;
        }
        name.truncate(cut);
        o.line(&format!("\\Problem name: {}", name.trim()))?;
    }
    for line in opts.comments.iter().flat_map(|c| c.lines()) {
        o.line(&format!("\\ {line}"))?;
    }
    let negate = model.sense == Sense::Maximize && opts.negate_max;
    if negate {
        o.line(NEGATED_MAX_COMMENT)?;
        o.line("\\ (the model maximises the negation of the objective below)")?;
    }
    o.line(if model.sense == Sense::Maximize && !negate { "Maximize" } else { "Minimize" })?;

    // Objective: every variable, in order, so that reading preserves the variable order.
    o.push(b" ");
    o.push(objective.as_bytes());
    o.push(b":");
    for (j, v) in model.vars().iter().enumerate() {
        let c = if negate { -v.obj } else { v.obj };
        term(&mut o, j == 0, c, &names[j])?;
    }
    let c0 = if negate { -model.obj_constant } else { model.obj_constant };
    if c0 != 0.0 {
        let s = fmt_signed(c0, &mut o.ryu);
        let piece = if let Some(abs) = s.strip_prefix('-') { format!(" - {abs}") } else { format!(" + {s}") };
        o.room(piece.len())?;
        o.push(piece.as_bytes());
    }
    o.newline()?;

    // Constraints.
    o.line("Subject To")?;
    for (i, r) in model.rows().enumerate() {
        match r.kind() {
            RowKind::Le => row(&mut o, &row_names[i], &r, &names, b" <=", r.rhs)?,
            RowKind::Ge => row(&mut o, &row_names[i], &r, &names, b" >=", r.lhs)?,
            RowKind::Eq => row(&mut o, &row_names[i], &r, &names, b" =", r.rhs)?,
            RowKind::Free => row(&mut o, &row_names[i], &r, &names, b" >=", f64::NEG_INFINITY)?,
            RowKind::Ranged => {
                o.line(RANGED_ROW_COMMENT)?;
                row(&mut o, &row_names[i], &r, &names, b" >=", r.lhs)?;
                let upper = range_upper[i].as_deref().unwrap_or("");
                row(&mut o, upper, &r, &names, b" <=", r.rhs)?;
            }
        }
    }

    // Bounds.
    let mut header = false;
    for (j, v) in model.vars().iter().enumerate() {
        let default = match v.kind {
            VarKind::Continuous => v.lb == 0.0 && v.ub == f64::INFINITY,
            VarKind::Integer => false,
            VarKind::Binary => v.lb == 0.0 && v.ub == 1.0,
        };
        if default {
            continue;
        }
        if !header {
            o.line("Bounds")?;
            header = true;
        }
        bound(&mut o, &names[j], v.lb, v.ub)?;
    }

    // Integrality.
    for (kind, title) in [(VarKind::Integer, "Generals"), (VarKind::Binary, "Binaries")] {
        let mut header = false;
        for (j, v) in model.vars().iter().enumerate() {
            if v.kind != kind {
                continue;
            }
            if !header {
                o.line(title)?;
                header = true;
            }
            let n = &names[j];
            o.room(n.len() + 1)?;
            o.push(b" ");
            o.push(n.as_bytes());
        }
        if header {
            o.newline()?;
        }
    }
    o.line("End")?;
    o.finish()?;
    Ok(map)
}

/// ` name: terms cmp value`.
fn row<W: Write>(
    o: &mut Out<W>,
    name: &str,
    r: &crate::milp::RowView,
    names: &[std::borrow::Cow<str>],
    cmp: &[u8],
    value: f64,
) -> io::Result<()> {
    o.push(b" ");
    o.push(name.as_bytes());
    o.push(b":");
    for (k, (v, a)) in r.terms().enumerate() {
        term(o, k == 0, a, &names[v.index()])?;
    }
    let s = fmt_signed(value, &mut o.ryu);
    o.room(cmp.len() + 1 + s.len())?;
    o.push(cmp);
    o.push(b" ");
    o.push(s.as_bytes());
    o.newline()
}

/// One variable's bounds (not the default ones).
fn bound<W: Write>(o: &mut Out<W>, name: &str, lb: f64, ub: f64) -> io::Result<()> {
    let l = fmt_signed(lb, &mut o.ryu);
    let u = fmt_signed(ub, &mut o.ryu);
    let line = if lb == ub {
        format!(" {name} = {u}")
    } else if lb == f64::NEG_INFINITY && ub == f64::INFINITY {
        format!(" {name} free")
    } else if ub == f64::INFINITY {
        format!(" {name} >= {l}")
    } else {
        let both = format!(" {l} <= {name} <= {u}");
        if both.len() <= o.max || lb == f64::NEG_INFINITY {
            both
        } else {
            o.line(&format!(" {name} >= {l}"))?;
            format!(" {name} <= {u}")
        }
    };
    o.line(&line)
}
