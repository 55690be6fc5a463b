//! The second objective in the solver-free model (docs/guide.md#layouts-like-the-demonstrations): one term per
//! object that synthesis places and whose class and size the like-scenes
//! showed, holding the object's grid variables and its distance map.
//!
//! An object with an orientation variable (`Model::turn_vars`) has no
//! term: its cost would depend on the orientation; `synthesize` with
//! `like` gives every orientation on its own (`synth::turns`).
//!
//! The cost of a term is `map.cost[gy·nx + gx]`; the total resemblance cost
//! is the sum of the terms (objects whose class and size were never shown
//! have no term: they add nothing). The map's domain is exactly the grid
//! variables' domain (`gx ∈ 0..=ub_x`), so every value the engine can
//! choose has a cost.

use super::model::{Coord, Model};
use crate::resemblance::{DistanceMap, ResemblanceError, ResemblanceTarget};
use crate::scene::Scene;

/// One object's share of the resemblance cost.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct ResemblanceTerm {
    /// The object (index into the problem's objects).
    pub object: usize,
    /// Its x grid variable (index into `Model::vars`).
    pub x: usize,
    /// Its y grid variable.
    pub y: usize,
    /// Cost per grid position, row-major over `(gy, gx)`.
    pub map: DistanceMap,
}

impl ResemblanceTerm {
    /// The cost at grid values `vals` (one per model variable).
    pub(crate) fn cost(&self, vals: &[i64]) -> u64 {
        let (gx, gy) = (vals[self.x], vals[self.y]);
        match (u64::try_from(gx), u64::try_from(gy)) {
            (Ok(gx), Ok(gy)) => self.map.at(gx, gy).unwrap_or(u64::MAX),
            _ => u64::MAX,
        }
    }
}

/// The terms of every unplaced object of `problem` in `model` (built from
/// the same problem).
pub(super) fn resemblance_terms(
    model: &Model,
    problem: &Scene,
    like: &ResemblanceTarget,
) -> Result<Vec<ResemblanceTerm>, ResemblanceError> {
    let mut out = Vec::new();
    // One map per class and size (objects of one class and size share it).
    let mut maps: std::collections::HashMap<(&str, i64, i64), Option<DistanceMap>> =
        std::collections::HashMap::new();
    for (i, o) in problem.objects.iter().enumerate() {
        let (Coord::Var(x), Coord::Var(y)) = model.coords[i] else {
            continue;
        };
        // An object with an orientation variable has no term: its map
        // would depend on the orientation (`synthesize` with `like`
        // solves each orientation choice on its own, without one).
        if model.turn_vars[i].is_some() {
            continue;
        }
        let (w, h) = o.footprint();
        let key = (o.class.as_str(), w, h);
        let map = match maps.get(&key) {
            Some(m) => m.clone(),
            None => {
                let m = like.distance_map(problem, o)?;
                maps.insert(key, m.clone());
                m
            }
        };
        if let Some(map) = map {
            debug_assert_eq!(map.nx, model.vars[x].ub as u64 + 1);
            debug_assert_eq!(map.ny, model.vars[y].ub as u64 + 1);
            out.push(ResemblanceTerm {
                object: i,
                x,
                y,
                map,
            });
        }
    }
    Ok(out)
}

/// The total cost of grid values `vals`.
pub(super) fn total_cost(terms: &[ResemblanceTerm], vals: &[i64]) -> u64 {
    terms
        .iter()
        .map(|t| t.cost(vals))
        .fold(0, u64::saturating_add)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::relations::Contact;
    use crate::rules::RuleSet;
    use crate::synth::model::BuildOptions;

    /// The model's terms give, on every layout of a tiny problem, the cost
    /// that the one resemblance function computes from the scene.
    #[test]
    fn terms_equal_the_resemblance_function_on_every_layout() {
        let problem = Scene::from_json(
            r#"{"space":{"x":3,"y":-2,"width":40,"height":30},"grid":10,"objects":[
              {"id":"a","class":"A","width":10,"height":10},
              {"id":"b","class":"B","width":20,"height":10},
              {"id":"z","class":"Z","width":10,"height":10},
              {"id":"w","class":"W","x":3,"y":-2,"width":5,"height":5,"fixed":true}]}"#,
        )
        .unwrap();
        let like = ResemblanceTarget::new(&[Scene::from_json(
            r#"{"space":{"x":3,"y":-2,"width":40,"height":30},"grid":10,"objects":[
              {"class":"A","x":21,"y":4,"width":10,"height":10},
              {"class":"B","x":3,"y":18,"width":20,"height":10},
              {"class":"B","x":33,"y":18,"width":10,"height":10}]}"#,
        )
        .unwrap()]);
        let model = Model::build(
            &problem,
            &RuleSet::default(),
            BuildOptions {
                contact: Contact::Point,
                rules: false,
                symmetry_breaking: false,
                redundant: false,
                tuning: Default::default(),
            },
        );
        let terms = resemblance_terms(&model, &problem, &like).unwrap();
        assert_eq!(terms.iter().map(|t| t.object).collect::<Vec<_>>(), [0, 1]);
        let ub: Vec<i64> = model.vars.iter().map(|v| v.ub).collect();
        let mut vals = vec![0i64; ub.len()];
        let mut seen = 0;
        'all: loop {
            let s = model.scene(&problem, &vals);
            assert_eq!(
                total_cost(&terms, &vals),
                like.cost(&problem, &s),
                "{vals:?}"
            );
            seen += 1;
            for i in 0..vals.len() {
                vals[i] += 1;
                if vals[i] <= ub[i] {
                    continue 'all;
                }
                vals[i] = 0;
            }
            break;
        }
        assert_eq!(seen, ub.iter().map(|u| u + 1).product::<i64>());
    }
}
