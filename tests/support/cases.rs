//! A random problem of the differential tests (`synth_differential`,
//! `ask_probes`) and the text that reproduces it by hand.

use rccpack::relations::Contact;
use rccpack::rules::{Rule, RuleSet, Scope, Strength};
use rccpack::scene::Scene;
use rccpack_bench::pool::formula_text;

/// One random problem.
#[derive(Debug, Clone)]
pub struct Case {
    /// Its index in the generator's stream.
    pub index: u64,
    /// The problem.
    pub scene: Scene,
    /// The rules.
    pub rules: RuleSet,
    /// The contact mode.
    pub contact: Contact,
}

impl Case {
    /// Everything needed to reproduce the case by hand.
    pub fn describe(&self) -> String {
        let mut s = format!(
            "case {} (contact {}):\n{}rules:\n",
            self.index,
            self.contact,
            self.scene.to_json()
        );
        for r in &self.rules.rules {
            let m = match r.strength {
                Strength::Hard => " hard".to_string(),
                Strength::Weight(w) if w != 1.0 => format!(" weight {w}"),
                _ => String::new(),
            };
            s.push_str(&format!("rule {}{m}: {}\n", r.name, rule_text(r)));
        }
        s
    }
}

/// A rule's scope and formula in the language (`some A: EC_N(A, B)`).
pub fn rule_text(r: &Rule) -> String {
    let scope = match r.scope {
        Scope::Each | Scope::Group => String::new(),
        Scope::Scene(q) => format!("{q} {}: ", r.subject()),
    };
    format!("{scope}{}", formula_text(&r.formula))
}
