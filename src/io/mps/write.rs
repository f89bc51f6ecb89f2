//! The free MPS writer. See the module documentation of [`super`] for the conventions.

use super::names::{clean, make_unique};
use super::{WriteOptions, BINARY_COMMENT_PREFIX, NEGATED_MAX_COMMENT, RANGE_COMMENT_PREFIX};
use crate::io::NameMap;
use crate::milp::{Model, RowKind, Sense, VarKind};
use std::borrow::Cow;
use std::io::{self, Write};

/// Flush the buffer to the writer beyond this many bytes.
const CHUNK: usize = 1 << 16;

/// An output buffer with the number formatter.
struct Out<'w, W: Write> {
    buf: Vec<u8>,
    w: &'w mut W,
    ryu: ryu::Buffer,
    align: bool,
}

impl<W: Write> Out<'_, W> {
    #[inline]
    fn s(&mut self, s: &str) {
        self.buf.extend_from_slice(s.as_bytes());
    }

    /// A name padded to 8 characters when aligning, followed by `gap` spaces.
    #[inline]
    fn field(&mut self, s: &str, gap: usize) {
        self.buf.extend_from_slice(s.as_bytes());
        if self.align {
            let pad = 8usize.saturating_sub(s.len()) + gap;
            self.buf.extend_from_slice(&b"                "[..pad.min(16)]);
        } else {
            self.buf.push(b' ');
        }
    }

    /// A finite number in its shortest round-trip form (`3` rather than `3.0`), padded to
    /// `width` when aligning.
    #[inline]
    fn num(&mut self, v: f64, width: usize) {
        let start = self.buf.len();
        if v == 0.0 {
            self.buf.extend_from_slice(if v.is_sign_negative() { b"-0" } else { b"0" });
        } else {
            let s = self.ryu.format_finite(v);
            let s = s.strip_suffix(".0").unwrap_or(s);
            self.buf.extend_from_slice(s.as_bytes());
        }
        if self.align {
            let len = self.buf.len() - start;
            if len < width {
                self.buf.resize(start + width, b' ');
            }
        }
    }

    /// The gap between the two (name, value) pairs of a line.
    #[inline]
    fn pair_gap(&mut self) {
        self.s(if self.align { "   " } else { " " });
    }

    #[inline]
    fn nl(&mut self) -> io::Result<()> {
        self.buf.push(b'\n');
        if self.buf.len() >= CHUNK {
            self.w.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    fn finish(mut self) -> io::Result<()> {
        self.w.write_all(&self.buf)?;
        self.buf.clear();
        self.w.flush()
    }
}

fn invalid(msg: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, msg)
}

/// Rejects models that have no MPS form.
fn check(model: &Model) -> io::Result<()> {
    if !model.obj_constant.is_finite() {
        return Err(invalid(format!("objective constant {} is not finite", model.obj_constant)));
    }
    for v in model.vars() {
        if !v.obj.is_finite() {
            return Err(invalid(format!("objective coefficient {} of `{}` is not finite", v.obj, v.name)));
        }
        if v.lb.is_nan() || v.ub.is_nan() || v.lb == f64::INFINITY || v.ub == f64::NEG_INFINITY {
            return Err(invalid(format!("variable `{}` has unusable bounds [{}, {}]", v.name, v.lb, v.ub)));
        }
    }
    let (lhs, rhs) = model.row_sides();
    let (_, _, coefs) = model.csr();
    if let Some(a) = coefs.iter().find(|a| !a.is_finite()) {
        return Err(invalid(format!("matrix coefficient {a} is not finite")));
    }
    for (r, (&l, &u)) in lhs.iter().zip(rhs).enumerate() {
        if l.is_nan() || u.is_nan() || l == f64::INFINITY || u == f64::NEG_INFINITY || l > u {
            let name = model.row(crate::milp::RowId(r as u32)).name;
            return Err(invalid(format!("row `{name}` has unusable sides [{l}, {u}]")));
        }
    }
    Ok(())
}

/// How a row is written: its type letter, the RHS value, an optional RANGES value, and whether
/// the two sides read back exactly from these.
fn row_form(lhs: f64, rhs: f64) -> (&'static str, f64, Option<f64>, bool) {
    match crate::milp::row_kind(lhs, rhs) {
        RowKind::Le => ("L", rhs, None, true),
        RowKind::Ge => ("G", lhs, None, true),
        RowKind::Eq => ("E", rhs, None, true),
        RowKind::Free => ("N", 0.0, None, true),
        RowKind::Ranged => {
            // A G row [b, b + R] or an L row [b - R, b], whichever reads back exactly.
            let r0 = rhs - lhs;
            let mut cand = [r0; 5];
            cand[1] = r0.next_up();
            cand[2] = r0.next_down();
            cand[3] = cand[1].next_up();
            cand[4] = cand[2].next_down();
            for r in cand {
                if r > 0.0 && r.is_finite() {
                    if lhs + r == rhs {
                        return ("G", lhs, Some(r), true);
                    }
                    if rhs - r == lhs {
                        return ("L", rhs, Some(r), true);
                    }
                }
            }
            // `rhs - lhs` is not representable: no RANGES value gives both sides exactly. Other
            // readers get the sides within an ulp; ours reads the exact ones from a comment.
            ("G", lhs, Some(r0), false)
        }
    }
}

pub(super) fn write<W: Write>(model: &Model, w: &mut W, opts: &WriteOptions) -> io::Result<NameMap> {
    check(model)?;

    // Names.
    let obj_name: Cow<str> =
        if model.objective_name.is_empty() { Cow::Borrowed("obj") } else { clean(&model.objective_name) };
    let row_orig: Vec<&str> = model.rows().map(|r| r.name).collect();
    let (row_names, row_changes) = make_unique(&[obj_name.as_ref()], row_orig.iter().copied(), false);
    let (col_names, col_changes) = make_unique(&[], model.vars().iter().map(|v| v.name.as_str()), true);
    let mut map = NameMap::default();
    for (i, new) in col_changes {
        map.vars.insert(model.vars()[i].name.clone(), new);
    }
    for (i, new) in row_changes {
        map.rows.insert(row_orig[i].to_string(), new);
    }
    if obj_name != model.objective_name && !row_orig.contains(&model.objective_name.as_str()) {
        map.rows.insert(model.objective_name.clone(), obj_name.to_string());
    }

    let negate = model.sense == Sense::Maximize && opts.negate_max;
    let mut o = Out { buf: Vec::with_capacity(CHUNK + 4096), w, ryu: ryu::Buffer::new(), align: opts.align };

    // Header.
    for line in opts.comments.iter().flat_map(|c| c.lines()) {
        o.s("* ");
        o.s(line);
        o.nl()?;
    }
    if negate {
        o.s(NEGATED_MAX_COMMENT);
        o.nl()?;
    }
    let title: String =
        model.name.chars().map(|c| if c.is_control() { '_' } else { c }).collect::<String>().trim().to_string();
    o.s("NAME");
    if !title.is_empty() {
        o.s(if opts.align { "          " } else { " " });
        o.s(&title);
    }
    o.nl()?;
    if model.sense == Sense::Maximize && !negate {
        o.s("OBJSENSE");
        o.nl()?;
        o.s("    MAX");
        o.nl()?;
    }

    // ROWS.
    let (lhs, rhs) = model.row_sides();
    let forms: Vec<(&'static str, f64, Option<f64>, bool)> =
        lhs.iter().zip(rhs).map(|(&l, &u)| row_form(l, u)).collect();
    o.s("ROWS");
    o.nl()?;
    o.s(" N  ");
    o.s(&obj_name);
    o.nl()?;
    for (form, name) in forms.iter().zip(&row_names) {
        o.s(" ");
        o.s(form.0);
        o.s("  ");
        o.s(name);
        o.nl()?;
    }

    // COLUMNS.
    o.s("COLUMNS");
    o.nl()?;
    let (start, rows, vals) = model.to_csc();
    let mut in_int = false;
    let mut pairs: Vec<(&str, f64)> = Vec::new();
    for (j, v) in model.vars().iter().enumerate() {
        let integral = v.kind.is_integral();
        if integral != in_int {
            o.s("    MARKER    'MARKER'                 ");
            o.s(if integral { "'INTORG'" } else { "'INTEND'" });
            o.nl()?;
            in_int = integral;
        }
        let name = col_names[j].as_ref();
        let (s, e) = (start[j], start[j + 1]);
        pairs.clear();
        let obj = if negate { -v.obj } else { v.obj };
        if obj != 0.0 || s == e {
            pairs.push((obj_name.as_ref(), if obj == 0.0 { 0.0 } else { obj }));
        }
        for k in s..e {
            pairs.push((row_names[rows[k] as usize].as_ref(), vals[k]));
        }
        for chunk in pairs.chunks(2) {
            o.s("    ");
            o.field(name, 2);
            o.field(chunk[0].0, 2);
            if chunk.len() == 2 {
                o.num(chunk[0].1, 12);
                o.pair_gap();
                o.field(chunk[1].0, 2);
                o.num(chunk[1].1, 0);
            } else {
                o.num(chunk[0].1, 0);
            }
            o.nl()?;
        }
    }
    if in_int {
        o.s("    MARKER    'MARKER'                 'INTEND'");
        o.nl()?;
    }

    // RHS.
    pairs.clear();
    if model.obj_constant != 0.0 {
        // The RHS of the objective is minus the constant of the objective as written.
        let c = if negate { model.obj_constant } else { -model.obj_constant };
        pairs.push((obj_name.as_ref(), c));
    }
    for (r, form) in forms.iter().enumerate() {
        if form.0 != "N" && form.1 != 0.0 {
            pairs.push((row_names[r].as_ref(), form.1));
        }
    }
    // The header is written even when empty: SCIP's reader requires RHS after COLUMNS.
    o.s("RHS");
    o.nl()?;
    write_vector(&mut o, "RHS", &pairs)?;

    // RANGES.
    pairs.clear();
    for (r, form) in forms.iter().enumerate() {
        if let Some(range) = form.2 {
            pairs.push((row_names[r].as_ref(), range));
        }
    }
    if !pairs.is_empty() {
        o.s("RANGES");
        o.nl()?;
        for (r, form) in forms.iter().enumerate() {
            if !form.3 {
                o.s(RANGE_COMMENT_PREFIX);
                o.s(&row_names[r]);
                o.s(" ");
                o.num(lhs[r], 0);
                o.s(" ");
                o.num(rhs[r], 0);
                o.nl()?;
            }
        }
        write_vector(&mut o, "RNG", &pairs)?;
    }

    // BOUNDS.
    let mut header = false;
    for (j, v) in model.vars().iter().enumerate() {
        let name = col_names[j].as_ref();
        let (lb, ub) = (v.lb, v.ub);
        let mut lines: [(&str, Option<f64>); 2] = [("", None); 2];
        let mut count = 0;
        let mut push = |t: &'static str, val: Option<f64>| {
            lines[count] = (t, val);
            count += 1;
        };
        // A binary whose bounds are not [0, 1] is written as an integer column plus a comment
        // that our reader understands.
        let binary_comment = v.kind == VarKind::Binary && !(lb == 0.0 && ub == 1.0);
        match v.kind {
            VarKind::Binary if lb == 0.0 && ub == 1.0 => push("BV", None),
            VarKind::Continuous if lb == 0.0 && ub == f64::INFINITY => {}
            _ if lb == ub => push("FX", Some(lb)),
            _ if lb == f64::NEG_INFINITY && ub == f64::INFINITY => push("FR", None),
            kind => {
                let integral = kind.is_integral();
                // Lower side first, so that a negative upper bound is never read as "no lower
                // bound given" (which some readers turn into -inf).
                if lb == f64::NEG_INFINITY {
                    push("MI", None);
                } else if integral || lb != 0.0 || ub < 0.0 {
                    push("LO", Some(lb));
                }
                if ub != f64::INFINITY {
                    push("UP", Some(ub));
                } else if integral {
                    push("PL", None);
                }
            }
        }
        if count == 0 {
            continue;
        }
        if !header {
            o.s("BOUNDS");
            o.nl()?;
            header = true;
        }
        if binary_comment {
            o.s(BINARY_COMMENT_PREFIX);
            o.s(name);
            o.nl()?;
        }
        for &(t, val) in &lines[..count] {
            o.s(" ");
            o.s(t);
            o.s(" ");
            o.field("BND", 2);
            match val {
                Some(x) => {
                    o.field(name, 2);
                    o.num(x, 0);
                }
                None => o.s(name),
            }
            o.nl()?;
        }
    }

    o.s("ENDATA");
    o.nl()?;
    o.finish()?;
    Ok(map)
}

/// Writes RHS or RANGES entries, two per line.
fn write_vector<W: Write>(o: &mut Out<'_, W>, set: &str, pairs: &[(&str, f64)]) -> io::Result<()> {
    for chunk in pairs.chunks(2) {
        o.s("    ");
        o.field(set, 2);
        o.field(chunk[0].0, 2);
        if chunk.len() == 2 {
            o.num(chunk[0].1, 12);
            o.pair_gap();
            o.field(chunk[1].0, 2);
            o.num(chunk[1].1, 0);
        } else {
            o.num(chunk[0].1, 0);
        }
        o.nl()?;
    }
    Ok(())
}
