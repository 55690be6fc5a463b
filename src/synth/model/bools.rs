//! The model's Booleans: hash-consed exact definitions (bounds of one grid
//! variable, bounds on a difference of two, conjunctions, counts), folded
//! to constants where the domains decide them.

use super::{BoolDef, Coord, Lit, Model};
use crate::relations::{Axis, Quant};

pub(super) fn ceil_div(a: i64, b: i64) -> i64 {
    -((-a).div_euclid(b))
}

pub(super) fn floor_div(a: i64, b: i64) -> i64 {
    a.div_euclid(b)
}

impl Model {
    pub(super) fn intern(&mut self, def: BoolDef) -> Lit {
        if let Some(&id) = self.interned.get(&def) {
            return Lit::pos(id);
        }
        let id = self.bools.len() as u32;
        self.bools.push(def.clone());
        self.interned.insert(def, id);
        Lit::pos(id)
    }

    /// `vars[v] ≥ k`.
    pub(super) fn ge(&mut self, v: usize, k: i64) -> Lit {
        if k <= 0 {
            Lit::TRUE
        } else if k > self.vars[v].ub {
            Lit::FALSE
        } else {
            self.intern(BoolDef::Ge { var: v, k })
        }
    }

    /// `vars[a] − vars[b] ≥ k`.
    pub(super) fn vdiff_ge(&mut self, a: usize, b: usize, k: i64) -> Lit {
        if k <= -self.vars[b].ub {
            Lit::TRUE
        } else if k > self.vars[a].ub {
            Lit::FALSE
        } else if a > b {
            // a − b ≥ k  ⇔  ¬(b − a ≥ 1 − k)
            !self.vdiff_ge(b, a, 1 - k)
        } else {
            self.intern(BoolDef::DiffGe { a, b, k })
        }
    }

    /// `coord(a) − coord(b) ≥ d` in real units.
    pub(super) fn diff_ge(&mut self, axis: Axis, a: usize, b: usize, d: i64) -> Lit {
        let o = self.axis_origin(axis);
        let g = self.grid;
        match (self.coord(a, axis), self.coord(b, axis)) {
            (Coord::Const(ca), Coord::Const(cb)) => Lit::Const(ca - cb >= d),
            (Coord::Var(va), Coord::Const(cb)) => self.ge(va, ceil_div(d + cb - o, g)),
            (Coord::Const(ca), Coord::Var(vb)) => !self.ge(vb, floor_div(ca - o - d, g) + 1),
            (Coord::Var(va), Coord::Var(vb)) => self.vdiff_ge(va, vb, ceil_div(d, g)),
        }
    }

    /// Conjunction with folding (constants, duplicates, complements).
    pub fn and(&mut self, lits: Vec<Lit>) -> Lit {
        let mut v = Vec::with_capacity(lits.len());
        for l in lits {
            match l {
                Lit::Const(true) => {}
                Lit::Const(false) => return Lit::FALSE,
                _ => v.push(l),
            }
        }
        v.sort_unstable();
        v.dedup();
        for w in v.windows(2) {
            if let (Lit::Var { id: i, .. }, Lit::Var { id: j, .. }) = (w[0], w[1]) {
                if i == j {
                    return Lit::FALSE;
                }
            }
        }
        match v.len() {
            0 => Lit::TRUE,
            1 => v[0],
            _ => self.intern(BoolDef::And(v)),
        }
    }

    /// Disjunction (the dual of [`Model::and`]).
    pub fn or(&mut self, lits: Vec<Lit>) -> Lit {
        let neg = lits.into_iter().map(|l| !l).collect();
        !self.and(neg)
    }

    /// At least `k` of `lits` (a multiset) hold, folded where it can be.
    ///
    /// Constants are counted off; a literal and its complement together
    /// always count exactly one, so such pairs are counted off too. What is
    /// left holds at most one polarity of each Boolean (repeats kept with
    /// their multiplicity), so the engine never sees one solver variable
    /// twice in a count.
    pub fn at_least(&mut self, lits: Vec<Lit>, k: u32) -> Lit {
        let mut need = i64::from(k);
        let mut vars: Vec<(u32, bool)> = Vec::with_capacity(lits.len());
        for l in lits {
            match l {
                Lit::Const(true) => need -= 1,
                Lit::Const(false) => {}
                Lit::Var { id, neg } => vars.push((id, neg)),
            }
        }
        // Sorted, `l` and `¬l` are adjacent (same id, `neg` false first).
        vars.sort_unstable();
        let mut v = Vec::with_capacity(vars.len());
        for group in vars.chunk_by(|a, b| a.0 == b.0) {
            let id = group[0].0;
            let neg = group.iter().filter(|l| l.1).count();
            let pos = group.len() - neg;
            let pairs = pos.min(neg);
            need -= pairs as i64;
            let rest = Lit::Var { id, neg: neg > pos };
            v.extend(std::iter::repeat_n(rest, pos.max(neg) - pairs));
        }
        if need <= 0 {
            return Lit::TRUE;
        }
        let n = v.len() as i64;
        if need > n {
            Lit::FALSE
        } else if need == 1 {
            self.or(v)
        } else if need == n {
            self.and(v)
        } else {
            self.intern(BoolDef::AtLeast {
                lits: v,
                k: need as u32,
            })
        }
    }

    /// The literal of quantifier `q` over `lits` (the table of docs/language.md#quantifiers).
    pub fn quantify(&mut self, q: Quant, lits: Vec<Lit>) -> Lit {
        match q {
            Quant::Every => self.and(lits),
            Quant::Some => self.or(lits),
            Quant::No => {
                let neg = lits.into_iter().map(|l| !l).collect();
                self.and(neg)
            }
            Quant::AtLeast(k) => self.at_least(lits, k),
            Quant::AtMost(k) => !self.at_least(lits, k.saturating_add(1)),
        }
    }
}
