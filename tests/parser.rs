//! Tests for the `.rcc` parser, checks, printer and diagnostics.

use proptest::prelude::*;
use rccpack::relations::Relation;
use rccpack::rules::*;
use rccpack::scene::Scene;

const PILOT: &str = "\
rule blue_north_of_red: DR_N(B, R)
rule green_east_of_red: DR_E(G, R)
rule green_east_of_blue: DR_E(G, B)
rule blue_touches_blue: EC_N(B, B) | EC_S(B, B) | EC_E(B, B) | EC_W(B, B)
rule red_touches_red: EC_N(R, R) | EC_S(R, R) | EC_E(R, R) | EC_W(R, R)
rule green_touches_green: EC_N(G, G) | EC_S(G, G) | EC_E(G, G) | EC_W(G, G)
rule blue_in_corner: (EC_N(B, *) & EC_W(B, *)) | (EC_W(B, *) & EC_S(B, *))
                   | (EC_S(B, *) & EC_E(B, *)) | (EC_E(B, *) & EC_N(B, *))
rule blue_inside: !DR_N(B, W) & !DR_S(B, W) & !DR_E(B, W) & !DR_W(B, W)
";

fn rel(n: &str) -> Relation {
    Relation::from_name(n).unwrap()
}

fn at(r: &str, s: &str, t: &str) -> Formula {
    let target = if t == "*" {
        Target::Any
    } else {
        Target::Class(t.to_string())
    };
    Formula::Atom(Atom::new(rel(r), s, target))
}

/// Parse one rule's formula (panics on error: for positive tests).
fn formula(src: &str) -> Formula {
    match parse_rules(src) {
        Ok(rs) => {
            assert_eq!(rs.rules.len(), 1, "{src}");
            rs.rules[0].formula.clone()
        }
        Err(e) => panic!("{src:?} failed:\n{}", e.render("t.rcc", src, false)),
    }
}

fn ok(src: &str) -> RuleSet {
    match parse_rules(src) {
        Ok(rs) => rs,
        Err(e) => panic!("{src:?} failed:\n{}", e.render("t.rcc", src, false)),
    }
}

/// The first diagnostic's message and its (line, col).
fn err(src: &str) -> (String, (usize, usize)) {
    match parse_rules(src) {
        Ok(rs) => panic!("{src:?} parsed: {rs:?}"),
        Err(e) => (e.diagnostics[0].message.clone(), e.line_col(src)),
    }
}

// ---- the worked example -----------------------------------------------------

#[test]
fn pilot_file_parses() {
    let rs = ok(PILOT);
    let names: Vec<&str> = rs.rules.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "blue_north_of_red",
            "green_east_of_red",
            "green_east_of_blue",
            "blue_touches_blue",
            "red_touches_red",
            "green_touches_green",
            "blue_in_corner",
            "blue_inside"
        ]
    );
    assert!(rs.rules.iter().all(|r| r.strength == Strength::Weight(1.0)));
    let corner = &rs.rules[6].formula;
    assert_eq!(
        *corner,
        Formula::Or(vec![
            Formula::And(vec![at("EC_N", "B", "*"), at("EC_W", "B", "*")]),
            Formula::And(vec![at("EC_W", "B", "*"), at("EC_S", "B", "*")]),
            Formula::And(vec![at("EC_S", "B", "*"), at("EC_E", "B", "*")]),
            Formula::And(vec![at("EC_E", "B", "*"), at("EC_N", "B", "*")]),
        ])
    );
    let inside = &rs.rules[7].formula;
    assert_eq!(
        *inside,
        Formula::And(
            ["DR_N", "DR_S", "DR_E", "DR_W"]
                .iter()
                .map(|r| Formula::not(at(r, "B", "W")))
                .collect()
        )
    );
    // Origins: atom spans in atoms() order, pointing at the atom text.
    for r in &rs.rules {
        let o = r.origin.as_ref().unwrap();
        assert_eq!(&PILOT[o.name.start..o.name.end], r.name);
        let atoms = r.formula.atoms();
        assert_eq!(atoms.len(), o.atoms.len());
        for (a, s) in atoms.iter().zip(&o.atoms) {
            let text: String = PILOT[s.start..s.end].split_whitespace().collect();
            assert_eq!(text, a.to_string().replace(' ', ""));
        }
    }
    // And it round-trips through the printer.
    let again = ok(&print_rules(&rs));
    assert!(again.same_rules(&rs));
}

#[test]
fn spec_example_parses() {
    let src = "\
# blue blocks go north of red ones, and every block sits inside the box
rule blue_north_of_red: DR_N(B, R)
rule green_east weight 2.5: DR_E(G, R)
rule green_east_of_blue p 1.0e-8: DR_E(G, B)
rule red_inside hard: !DR_N(R, W) & !DR_S(R, W) & !DR_E(R, W) & !DR_W(R, W)
";
    let rs = ok(src);
    assert_eq!(rs.rules[1].strength, Strength::Weight(2.5));
    assert_eq!(rs.rules[2].strength, Strength::P(1.0e-8));
    assert_eq!(rs.rules[3].strength, Strength::Hard);
}

// ---- one test per grammar rule ------------------------------------------

#[test]
fn grammar_file() {
    assert_eq!(ok("").rules.len(), 0);
    assert_eq!(ok("\n\n# only a comment\n   \n").rules.len(), 0);
    assert_eq!(ok("rule a: DR_N(B, R)").rules.len(), 1);
    // Two rules on one line are not a file.
    let (m, lc) = err("rule a: DR_N(B, R) rule b: DR_N(B, R)\n");
    assert!(m.starts_with("expected "), "{m}");
    assert!(m.ends_with("found `rule`"), "{m}");
    assert_eq!(lc, (1, 20));
}

#[test]
fn grammar_eol() {
    assert_eq!(
        ok("rule a: DR_N(B, R)\r\nrule b: DR_S(B, R)\r\n")
            .rules
            .len(),
        2
    );
    assert_eq!(
        ok("\n\nrule a: DR_N(B, R)\n\n\nrule b: DR_S(B, R)")
            .rules
            .len(),
        2
    );
    let (m, lc) = err("rule a: DR_N(B, R) DR_S(B, R)");
    assert_eq!(
        m,
        "expected end of input, end of line, `|` or `&`, found `DR_S`"
    );
    assert_eq!(lc, (1, 20));
}

#[test]
fn grammar_rule_def_and_kw_rule() {
    ok("rule a: DR_N(B, R)");
    ok("  rule\ta  :  DR_N( B ,R )  ");
    let (m, lc) = err("rules a: DR_N(B, R)");
    assert_eq!(m, "expected a rule, found `rules`");
    assert_eq!(lc, (1, 1));
    let (m, _) = err("a: DR_N(B, R)");
    assert_eq!(m, "expected a rule, found `a`");
}

#[test]
fn grammar_name() {
    assert_eq!(ok("rule _a1_B: DR_N(B, R)").rules[0].name, "_a1_B");
    // Keywords are fine as names.
    assert_eq!(ok("rule hard hard: DR_N(B, R)").rules[0].name, "hard");
    let (m, lc) = err("rule 1a: DR_N(B, R)");
    assert_eq!(m, "expected a rule name, found `1a`");
    assert_eq!(lc, (1, 6));
}

#[test]
fn grammar_colon() {
    ok("rule a : DR_N(B, R)");
    let (m, lc) = err("rule a DR_N(B, R)");
    assert_eq!(
        m,
        "expected `:` or a modifier (`weight W`, `p P` or `hard`), found `DR_N`"
    );
    assert_eq!(lc, (1, 8));
    let (m, _) = err("rule a hard DR_N(B, R)");
    assert_eq!(m, "expected `:`, found `DR_N`");
}

#[test]
fn grammar_modifier() {
    assert_eq!(
        ok("rule a hard: DR_N(B, R)").rules[0].strength,
        Strength::Hard
    );
    // At most one modifier.
    let (m, lc) = err("rule a hard weight 2: DR_N(B, R)");
    assert_eq!(m, "expected `:`, found `weight`");
    assert_eq!(lc, (1, 13));
}

#[test]
fn grammar_weight_mod_and_kw_weight() {
    assert_eq!(
        ok("rule a weight 2.5: DR_N(B, R)").rules[0].strength,
        Strength::Weight(2.5)
    );
    assert_eq!(
        ok("rule a weight 1: DR_N(B, R)").rules[0].strength,
        Strength::Weight(1.0)
    );
    let (m, _) = err("rule a weight: DR_N(B, R)");
    assert_eq!(m, "expected a number, found `:`");
    let (m, lc) = err("rule a weight 0: DR_N(B, R)");
    assert_eq!(m, "bad weight `0`: expected a finite number > 0");
    assert_eq!(lc, (1, 15));
    let (m, _) = err("rule a weight -2: DR_N(B, R)");
    assert_eq!(m, "bad weight `-2`: expected a finite number > 0");
    let (m, _) = err("rule a weight 1e999: DR_N(B, R)");
    assert_eq!(
        m,
        "bad weight `1e999`: it is not finite; expected a finite number > 0"
    );
    // `weights` is not the keyword.
    let (m, _) = err("rule a weights 2: DR_N(B, R)");
    assert!(m.contains("found `weights`"), "{m}");
}

#[test]
fn grammar_p_mod_and_kw_p() {
    assert_eq!(
        ok("rule a p 0.25: DR_N(B, R)").rules[0].strength,
        Strength::P(0.25)
    );
    assert_eq!(
        ok("rule a p 1e-300: DR_N(B, R)").rules[0].strength,
        Strength::P(1e-300)
    );
    let (m, lc) = err("rule a p 1.5: DR_N(B, R)");
    assert_eq!(m, "bad p `1.5`: expected a number with 0 < p < 1");
    assert_eq!(lc, (1, 10));
    for bad in ["0", "1", "1.0", "-0.5", "1e-400"] {
        let (m, _) = err(&format!("rule a p {bad}: DR_N(B, R)"));
        assert_eq!(
            m,
            format!("bad p `{bad}`: expected a number with 0 < p < 1")
        );
    }
    let (m, _) = err("rule a p 1e999: DR_N(B, R)");
    assert!(m.contains("not finite"), "{m}");
}

#[test]
fn grammar_hard_mod_and_kw_hard() {
    assert_eq!(
        ok("rule a hard : DR_N(B, R)").rules[0].strength,
        Strength::Hard
    );
    let (m, _) = err("rule a hardly: DR_N(B, R)");
    assert!(m.contains("found `hardly`"), "{m}");
}

#[test]
fn grammar_number() {
    for (t, v) in [
        ("2.5", 2.5),
        ("1", 1.0),
        ("1.0e-8", 1e-8),
        (".5", 0.5),
        ("3.", 3.0),
        ("2E+3", 2000.0),
    ] {
        let rs = ok(&format!("rule a weight {t}: DR_N(B, R)"));
        assert_eq!(rs.rules[0].strength, Strength::Weight(v), "{t}");
    }
    for bad in ["x", "1.2.3", "1e", "2x", "."] {
        assert!(
            parse_rules(&format!("rule a weight {bad}: DR_N(B, R)")).is_err(),
            "{bad}"
        );
    }
}

#[test]
fn grammar_formula_disjunction_conjunction_precedence() {
    let (a, b, c) = (
        at("DR_N", "B", "R"),
        at("DR_S", "B", "R"),
        at("EC_E", "B", "*"),
    );
    assert_eq!(
        formula("rule x: DR_N(B, R) | DR_S(B, R) & EC_E(B, *)"),
        Formula::Or(vec![a.clone(), Formula::And(vec![b.clone(), c.clone()])])
    );
    assert_eq!(
        formula("rule x: DR_N(B, R) & DR_S(B, R) | EC_E(B, *)"),
        Formula::Or(vec![Formula::And(vec![a.clone(), b.clone()]), c.clone()])
    );
    assert_eq!(
        formula("rule x: !DR_N(B, R) & DR_S(B, R)"),
        Formula::And(vec![Formula::not(a.clone()), b.clone()])
    );
    // Word forms.
    assert_eq!(
        formula("rule x: not DR_N(B, R) and DR_S(B, R) or EC_E(B, *)"),
        Formula::Or(vec![
            Formula::And(vec![Formula::not(a.clone()), b.clone()]),
            c.clone()
        ])
    );
    // Flattening and vanishing parentheses.
    assert_eq!(
        formula("rule x: DR_N(B, R) & (DR_S(B, R) & EC_E(B, *))"),
        Formula::And(vec![a.clone(), b.clone(), c.clone()])
    );
    assert_eq!(formula("rule x: ((DR_N(B, R)))"), a.clone());
    // A missing formula.
    let (m, lc) = err("rule x: ");
    assert_eq!(m, "expected a formula, found end of input");
    assert_eq!(lc, (1, 9));
    let (m, _) = err("rule x: DR_N(B, R) |");
    assert!(
        m.starts_with("expected ") && m.ends_with("found end of input"),
        "{m}"
    );
    let (m, _) = err("rule x: DR_N(B, R) & & DR_S(B, R)");
    assert!(m.ends_with("found `&`"), "{m}");
}

#[test]
fn grammar_unary_and_not_op() {
    let a = at("DR_N", "B", "R");
    assert_eq!(
        formula("rule x: !!DR_N(B, R)"),
        Formula::not(Formula::not(a.clone()))
    );
    assert_eq!(formula("rule x: not ! not DR_N(B, R)").depth(), 4);
    // `not` needs a word boundary; `notDR_N` is a (bad) relation name.
    let (m, _) = err("rule x: notDR_N(B, R)");
    assert!(m.starts_with("unknown relation `notDR_N`"), "{m}");
    let (m, _) = err("rule x: DR_N(B, R) !DR_S(B, R)");
    assert!(m.ends_with("found `!`"), "{m}");
}

#[test]
fn grammar_group_lparen_rparen() {
    let f = formula("rule x: !(DR_N(B, R) | DR_S(B, R))");
    assert_eq!(
        f,
        Formula::not(Formula::Or(vec![
            at("DR_N", "B", "R"),
            at("DR_S", "B", "R")
        ]))
    );
    let (m, lc) = err("rule x: (DR_N(B, R)\n");
    assert_eq!(m, "expected `)`, `|` or `&`, found end of line");
    assert_eq!(lc, (1, 20));
    let (m, _) = err("rule x: DR_N(B, R))");
    assert!(m.ends_with("found `)`"), "{m}");
    let (m, _) = err("rule x: ()");
    assert!(m.ends_with("found `)`"), "{m}");
}

#[test]
fn grammar_or_op_and_and_op() {
    assert_eq!(
        formula("rule x: DR_N(B, R) or DR_S(B, R)"),
        formula("rule x: DR_N(B, R) | DR_S(B, R)")
    );
    assert_eq!(
        formula("rule x: DR_N(B, R) and DR_S(B, R)"),
        formula("rule x: DR_N(B, R) & DR_S(B, R)")
    );
    assert!(parse_rules("rule x: DR_N(B, R) || DR_S(B, R)").is_err());
    assert!(parse_rules("rule x: DR_N(B, R) && DR_S(B, R)").is_err());
    // `order` is not `or` followed by `der`.
    assert!(parse_rules("rule x: DR_N(B, R) order DR_S(B, R)").is_err());
}

#[test]
fn grammar_atom_and_relation() {
    for r in Relation::ALL {
        let f = formula(&format!("rule x: {}(B, R)", r.name()));
        assert_eq!(
            f,
            Formula::Atom(Atom::new(r, "B", Target::Class("R".into())))
        );
    }
    let (m, lc) = err("rule x: DR_X(B, R)");
    assert_eq!(
        m,
        "unknown relation `DR_X`: expected one of DR_N, DR_S, DR_E, DR_W, EC_N, EC_S, EC_E, EC_W, FL_N, FL_S, FL_E, FL_W, AL_N, AL_S, AL_E, AL_W"
    );
    assert_eq!(lc, (1, 9));
    let (m, _) = err("rule x: XX(B,R)");
    assert!(m.starts_with("unknown relation `XX`"), "{m}");
    let (m, _) = err("rule x: dr_n(B,R)");
    assert!(m.starts_with("unknown relation `dr_n`"), "{m}");
    let (m, lc) = err("rule x: DR_N B, R)");
    assert_eq!(m, "expected `(`, found `B`");
    assert_eq!(lc, (1, 14));
}

#[test]
fn grammar_comma_subject_target() {
    assert_eq!(formula("rule x: EC_W(B,*)"), at("EC_W", "B", "*"));
    assert_eq!(
        formula("rule x: EC_W( Blue_1 , red )"),
        at("EC_W", "Blue_1", "red")
    );
    let (m, lc) = err("rule x: DR_N(B R)");
    assert_eq!(m, "expected `,`, found `R`");
    assert_eq!(lc, (1, 16));
    let (m, _) = err("rule x: DR_N(*, R)");
    assert_eq!(m, "expected a class name, found `*`");
    let (m, _) = err("rule x: DR_N(B, 1)");
    assert_eq!(m, "expected a class name or `*`, found `1`");
}

#[test]
fn grammar_continuation() {
    let f = formula(
        "rule x: DR_N(B, R)\n  | DR_S(B, R)\n\t& EC_E(B, *)\n   or EC_W(B, *)\n and EC_N(B, *)",
    );
    assert_eq!(f.atoms().len(), 5);
    // Blank lines before a continuation are allowed.
    assert_eq!(
        formula("rule x: DR_N(B, R)\n\n  | DR_S(B, R)")
            .atoms()
            .len(),
        2
    );
    // A line starting with anything else is not a continuation.
    assert!(parse_rules("rule x: DR_N(B, R)\n  DR_S(B, R)").is_err());
    assert!(parse_rules("rule x: DR_N(B, R)\n  ! DR_S(B, R)").is_err());
    // `order` at line start is not a continuation.
    assert!(parse_rules("rule x: DR_N(B, R)\norder").is_err());
}

#[test]
fn grammar_comment_and_whitespace() {
    let rs =
        ok("# head\nrule x: DR_N(B, R) # tail ( (( ((\n\t # indented\nrule y:\tDR_S( B ,\tR )#x");
    assert_eq!(rs.rules.len(), 2);
    // `//` is not a comment.
    assert!(parse_rules("// no\nrule x: DR_N(B, R)").is_err());
    // A comment cannot hide the colon.
    assert!(parse_rules("rule x # : \n: DR_N(B, R)").is_err());
}

// ---- second edition (docs/language.md): one test per new grammar rule ------------------

const SECOND: &str = "\
rule blue_row:        AL_S(B, every B) & (FL_E(B, B) | FL_W(B, B))
rule blue_flush:      (!EC_N(B, B) | FL_N(B, B)) & (!EC_S(B, B) | FL_S(B, B))
                    & (!EC_E(B, B) | FL_E(B, B)) & (!EC_W(B, B) | FL_W(B, B))
rule red_apart_green: EC_N(R, no G) & EC_S(R, no G) & EC_E(R, no G) & EC_W(R, no G)
rule one_red_west:    some R: EC_E(R, @w_west) | FL_E(R, @w_west)
rule two_stacked:     at least 2 G: FL_N(G, G)
rule few_west p 0.01: at most 3 B: AL_W(B, at least 1 *) & !DR_W(B, @w_east)
";

fn atq(r: &str, s: &str, q: Quant, t: &str) -> Formula {
    Formula::Atom(Atom::quantified(rel(r), s, q, Target::Class(t.to_string())))
}

fn lm(r: &str, s: &str, id: &str) -> Formula {
    Formula::Atom(Atom::new(rel(r), s, Target::Landmark(id.to_string())))
}

/// The first rule's scope.
fn scope(src: &str) -> Scope {
    ok(src).rules[0].scope
}

#[test]
fn spec_second_edition_example_parses_and_round_trips() {
    let rs = ok(SECOND);
    assert_eq!(rs.rules.len(), 6);
    assert_eq!(
        rs.rules[0].formula,
        Formula::And(vec![
            atq("AL_S", "B", Quant::Every, "B"),
            Formula::Or(vec![at("FL_E", "B", "B"), at("FL_W", "B", "B")]),
        ])
    );
    assert_eq!(rs.rules[2].formula.atoms()[0].quant, Quant::No);
    assert_eq!(rs.rules[3].scope, Scope::Scene(Quant::Some));
    assert_eq!(
        rs.rules[3].formula,
        Formula::Or(vec![lm("EC_E", "R", "w_west"), lm("FL_E", "R", "w_west")])
    );
    assert_eq!(rs.rules[4].scope, Scope::Scene(Quant::AtLeast(2)));
    assert_eq!(rs.rules[5].scope, Scope::Scene(Quant::AtMost(3)));
    assert_eq!(rs.rules[5].strength, Strength::P(0.01));
    assert_eq!(rs.rules[0].scope, Scope::Each);
    assert_eq!(rs.landmarks(), ["w_east", "w_west"]);
    // Origins: atom spans cover the atom text, the scope span `Q A:`.
    for r in &rs.rules {
        let o = r.origin.as_ref().unwrap();
        for (a, s) in r.formula.atoms().iter().zip(&o.atoms) {
            let text: String = SECOND[s.start..s.end].split_whitespace().collect();
            assert_eq!(text, a.to_string().replace(' ', ""));
        }
    }
    let scopes: Vec<Option<&str>> = rs
        .rules
        .iter()
        .map(|r| {
            let o = r.origin.as_ref().unwrap();
            o.scope.map(|s| &SECOND[s.start..s.end])
        })
        .collect();
    assert_eq!(
        scopes,
        [
            None,
            None,
            None,
            Some("some R:"),
            Some("at least 2 G:"),
            Some("at most 3 B:")
        ]
    );
    let printed = print_rules(&rs);
    assert!(
        printed.contains("rule one_red_west: some R: EC_E(R, @w_west) | FL_E(R, @w_west)\n"),
        "{printed}"
    );
    assert!(
        printed.contains("rule two_stacked: at least 2 G: FL_N(G, G)\n"),
        "{printed}"
    );
    assert!(
        printed.contains(
            "rule few_west p 0.01: at most 3 B: AL_W(B, at least 1 *) & !DR_W(B, @w_east)\n"
        ),
        "{printed}"
    );
    assert!(ok(&printed).same_rules(&rs));
}

#[test]
fn default_quantifier_is_implicit() {
    // `DR_N(B, every R)` is `DR_N(B, R)` and prints as it.
    let explicit = ok("rule x: DR_N(B, every R)");
    let implicit = ok("rule x: DR_N(B, R)");
    assert!(explicit.same_rules(&implicit));
    assert_eq!(explicit.rules[0].formula, at("DR_N", "B", "R"));
    assert_eq!(print_rules(&explicit), "rule x: DR_N(B, R)\n");
    // Likewise `some` for EC, FL and AL.
    for r in ["EC_N", "FL_S", "AL_E"] {
        let rs = ok(&format!("rule x: {r}(B, some *)"));
        assert_eq!(rs.rules[0].formula, at(r, "B", "*"));
        assert_eq!(print_rules(&rs), format!("rule x: {r}(B, *)\n"));
    }
    // A non-default quantifier is written out.
    let rs = ok("rule x: DR_N(B, some R) & EC_N(B, every R)");
    assert_eq!(
        print_rules(&rs),
        "rule x: DR_N(B, some R) & EC_N(B, every R)\n"
    );
}

#[test]
fn grammar_body() {
    // A body is an optional scope and a formula.
    assert_eq!(scope("rule x: DR_N(B, R)"), Scope::Each);
    assert_eq!(
        scope("rule x: some B: DR_N(B, R)"),
        Scope::Scene(Quant::Some)
    );
    // A missing body is a missing formula, with or without a scope.
    let (m, lc) = err("rule x:");
    assert_eq!(m, "expected a formula, found end of input");
    assert_eq!(lc, (1, 8));
    let (m, lc) = err("rule x: no B:\n");
    assert_eq!(m, "expected a formula, found end of line");
    assert_eq!(lc, (1, 14));
}

#[test]
fn grammar_scope() {
    for (q, want) in [
        ("some", Scope::Scene(Quant::Some)),
        ("no", Scope::Scene(Quant::No)),
        ("at least 2", Scope::Scene(Quant::AtLeast(2))),
        ("at most 0", Scope::Scene(Quant::AtMost(0))),
        ("at  least\t65535", Scope::Scene(Quant::AtLeast(65535))),
        // `every A:` is the ordinary per-object rule.
        ("every", Scope::Each),
    ] {
        let src = format!("rule x weight 2: {q} G: FL_N(G, G) | !AL_S(G, *)");
        let rs = ok(&src);
        assert_eq!(rs.rules[0].scope, want, "{src}");
        assert_eq!(rs.rules[0].strength, Strength::Weight(2.0));
        let o = rs.rules[0].origin.as_ref().unwrap();
        let s = o.scope.unwrap();
        assert_eq!(&src[s.start..s.end], format!("{q} G:"));
    }
    // `every G:` is written as nothing.
    assert_eq!(
        print_rules(&ok("rule x: every G: FL_N(G, G)")),
        "rule x: FL_N(G, G)\n"
    );
    assert!(ok("rule x: every G: FL_N(G, G)").same_rules(&ok("rule x: FL_N(G, G)")));
    // A scope whose quantifier word is followed by no class is a relation.
    let (m, _) = err("rule x: some(B, R)");
    assert!(m.starts_with("unknown relation `some`"), "{m}");
    let (m, lc) = err("rule x: some B EC_N(B, R)");
    assert_eq!(m, "expected `:`, found `EC_N`");
    assert_eq!(lc, (1, 16));
}

#[test]
fn grammar_scope_colon() {
    ok("rule x: some G :FL_N(G, G)");
    ok("rule x: some G:FL_N(G, G)");
    let (m, _) = err("rule x: some G; FL_N(G, G)");
    assert_eq!(m, "expected `:`, found `;`");
    // One scope only.
    let (m, lc) = err("rule x: some G: no G: FL_N(G, G)");
    assert_eq!(m, "expected `(`, found `G`");
    assert_eq!(lc, (1, 20));
}

#[test]
fn grammar_subject() {
    assert_eq!(formula("rule x: FL_N( Blue , R )"), at("FL_N", "Blue", "R"));
    // `*` and landmarks are parsed but are not subjects (docs/language.md#syntax).
    let (m, lc) = err("rule x: DR_N(*, R)");
    assert_eq!(m, "expected a class name, found `*`");
    assert_eq!(lc, (1, 14));
    let (m, lc) = err("rule x: DR_N(@w_west, R)");
    assert_eq!(
        m,
        "expected a class name, found `@w_west`: the subject of an atom is a class, not a landmark"
    );
    assert_eq!(lc, (1, 14));
    let (m, lc) = err("rule x: some *: DR_N(B, R)");
    assert_eq!(
        m,
        "expected a class name after `some`, found `*`: a scene scope counts the objects of one class"
    );
    assert_eq!(lc, (1, 14));
    let (m, lc) = err("rule x: at least 2 @w: DR_N(B, R)");
    assert_eq!(
        m,
        "expected a class name after `at least 2`, found `@w`: a scene scope counts the objects of one class, not a landmark"
    );
    assert_eq!(lc, (1, 20));
    let (m, _) = err("rule x: DR_N(1, R)");
    assert_eq!(m, "expected a class name, found `1`");
}

#[test]
fn grammar_target_and_object() {
    assert_eq!(
        formula("rule x: EC_N(B, no G)"),
        atq("EC_N", "B", Quant::No, "G")
    );
    assert_eq!(
        formula("rule x: EC_N(B, at most 2 *)"),
        Formula::Atom(Atom::quantified(
            rel("EC_N"),
            "B",
            Quant::AtMost(2),
            Target::Any
        ))
    );
    assert_eq!(formula("rule x: EC_N(B,@w)"), lm("EC_N", "B", "w"));
    let (m, lc) = err("rule x: DR_N(B, )");
    assert_eq!(m, "expected a class name or `*`, found `)`");
    assert_eq!(lc, (1, 17));
    // After a quantifier the object is still missing.
    let (m, lc) = err("rule x: DR_N(B, at most 2)");
    assert_eq!(m, "expected a class name or `*`, found `)`");
    assert_eq!(lc, (1, 26));
    // Two quantifiers are not a target.
    let (m, lc) = err("rule x: DR_N(B, some no R)");
    assert_eq!(m, "expected `)`, found `R`");
    assert_eq!(lc, (1, 25));
}

#[test]
fn grammar_class_and_any() {
    assert_eq!(formula("rule x: AL_S(_b1, R_2)"), at("AL_S", "_b1", "R_2"));
    assert_eq!(formula("rule x: AL_S(B, *)"), at("AL_S", "B", "*"));
    assert_eq!(formula("rule x: AL_S(B, every *)"), {
        Formula::Atom(Atom::quantified(
            rel("AL_S"),
            "B",
            Quant::Every,
            Target::Any,
        ))
    });
    let (m, _) = err("rule x: AL_S(B, **)");
    assert_eq!(m, "expected `)`, found `*`");
}

#[test]
fn grammar_landmark_and_landmark_id() {
    assert_eq!(
        formula("rule x: EC_E(B, @w_west) & !DR_N(B, @_1)"),
        Formula::And(vec![
            lm("EC_E", "B", "w_west"),
            Formula::not(lm("DR_N", "B", "_1"))
        ])
    );
    // A landmark atom has the relation's default quantifier.
    let f = formula("rule x: DR_N(B, @w)");
    assert!(f.atoms()[0].has_default_quant());
    assert_eq!(print_formula(&f), "DR_N(B, @w)");
    // `@` is followed directly by an identifier.
    let (m, lc) = err("rule x: EC_E(B, @ w_west)");
    assert_eq!(m, "expected an object id right after `@`, found ` `");
    assert_eq!(lc, (1, 18));
    let (m, _) = err("rule x: EC_E(B, @1)");
    assert_eq!(m, "expected an object id right after `@`, found `1`");
    let (m, _) = err("rule x: EC_E(B, @)");
    assert_eq!(m, "expected an object id right after `@`, found `)`");
    let (m, _) = err("rule x: EC_E(B, @w-1)");
    assert_eq!(m, "expected `)`, found `-`");
    // No quantifier before a landmark.
    for q in ["every", "some", "no", "at least 1", "at most 0"] {
        let src = format!("rule x: EC_E(B, {q} @w_west)");
        let (m, lc) = err(&src);
        assert_eq!(
            m,
            format!("quantifier `{q}` before landmark `@w_west`: a landmark takes no quantifier; expected `@w_west` alone"),
        );
        assert_eq!(lc, (1, 17));
    }
}

#[test]
fn grammar_quant() {
    for (q, want) in [
        ("every", Quant::Every),
        ("some", Quant::Some),
        ("no", Quant::No),
        ("at least 0", Quant::AtLeast(0)),
        ("at least 3", Quant::AtLeast(3)),
        ("at most 65535", Quant::AtMost(65535)),
        ("at most 007", Quant::AtMost(7)),
        ("at\tleast  2", Quant::AtLeast(2)),
    ] {
        let f = formula(&format!("rule x: FL_W(B, {q} R)"));
        assert_eq!(f, atq("FL_W", "B", want, "R"), "{q}");
    }
    // Quantifiers print in their normal form.
    assert_eq!(
        print_formula(&formula("rule x: FL_W(B, at\tleast  002 R)")),
        "FL_W(B, at least 2 R)"
    );
}

#[test]
fn grammar_kw_every_some_no_are_not_reserved() {
    // A quantifier word with no class, `*` or `@` after it is a class name.
    for (w, q) in [
        ("every", Quant::Every),
        ("some", Quant::Some),
        ("no", Quant::No),
    ] {
        assert_eq!(
            formula(&format!("rule x: DR_N(B, {w})")),
            at("DR_N", "B", w)
        );
        assert_eq!(
            formula(&format!("rule x: DR_N({w}, R)")),
            at("DR_N", w, "R")
        );
        // ... and a quantifier before a class of that name.
        assert_eq!(
            formula(&format!("rule x: EC_N(B, {w} {w})")),
            atq("EC_N", "B", q, w)
        );
        assert_eq!(
            formula(&format!("rule x: EC_N(B, {w}\t*)")),
            Formula::Atom(Atom::quantified(rel("EC_N"), "B", q, Target::Any))
        );
        // As the subject class of a scope, and the same word as its
        // quantifier.
        let rs = ok(&format!("rule x: no {w}: EC_N({w}, R)"));
        assert_eq!(rs.rules[0].scope, Scope::Scene(Quant::No));
        assert_eq!(rs.rules[0].subject(), w);
        assert!(ok(&print_rules(&rs)).same_rules(&rs));
        let rs = ok(&format!("rule x: {w} {w}: EC_N({w}, {w} {w})"));
        assert_eq!(rs.rules[0].scope, Scope::of(q));
        assert!(ok(&print_rules(&rs)).same_rules(&rs));
    }
    // Words that only begin like a quantifier are classes.
    assert_eq!(
        formula("rule x: DR_N(B, nothing)"),
        at("DR_N", "B", "nothing")
    );
    assert_eq!(
        formula("rule x: DR_N(B, everyone)"),
        at("DR_N", "B", "everyone")
    );
    assert_eq!(
        formula("rule x: DR_N(B, somebody)"),
        at("DR_N", "B", "somebody")
    );
    let (m, _) = err("rule x: DR_N(B, no_one R)");
    assert_eq!(m, "expected `)`, found `R`");
    // A quantifier word followed by `(` at the start of a formula is a
    // (bad) relation name.
    let (m, _) = err("rule x: no(B, R)");
    assert!(m.starts_with("unknown relation `no`"), "{m}");
}

#[test]
fn grammar_kw_at_least_most() {
    // `at` is a quantifier only when `least` or `most` follows.
    assert_eq!(formula("rule x: DR_N(B, at)"), at("DR_N", "B", "at"));
    assert_eq!(formula("rule x: DR_N(at, R)"), at("DR_N", "at", "R"));
    assert_eq!(
        formula("rule x: DR_N(B, at least 2 at)"),
        atq("DR_N", "B", Quant::AtLeast(2), "at")
    );
    assert_eq!(
        formula("rule x: DR_N(B, at most 1 least)"),
        atq("DR_N", "B", Quant::AtMost(1), "least")
    );
    let rs = ok("rule x: at least 1 at: DR_N(at, at most 2 most)");
    assert_eq!(rs.rules[0].scope, Scope::Scene(Quant::AtLeast(1)));
    assert!(ok(&print_rules(&rs)).same_rules(&rs));
    let (m, lc) = err("rule x: DR_N(B, at x)");
    assert_eq!(m, "expected `)`, `least` or `most`, found `x`");
    assert_eq!(lc, (1, 20));
    // `atleast` and `at leastwise` are not the words.
    let (m, _) = err("rule x: DR_N(B, atleast 2 R)");
    assert_eq!(m, "expected `)`, found `2`");
    let (m, _) = err("rule x: DR_N(B, at leastwise 2 R)");
    assert_eq!(m, "expected `)`, `least` or `most`, found `leastwise`");
    let (m, _) = err("rule x: at(B, R)");
    assert!(m.starts_with("unknown relation `at`"), "{m}");
}

#[test]
fn grammar_count() {
    for (k, v) in [("0", 0), ("1", 1), ("65535", 65535), ("000065535", 65535)] {
        let f = formula(&format!("rule x: AL_N(B, at least {k} R)"));
        assert_eq!(f, atq("AL_N", "B", Quant::AtLeast(v), "R"), "{k}");
    }
    // Anything else is a located error at the count.
    for bad in [
        "+2", "-1", "2.0", "2.", ".5", "1e1", "1E+1", "1e-1", "2x", "0x10",
    ] {
        let src = format!("rule x: AL_N(B, at least {bad} R)");
        let (m, lc) = err(&src);
        assert_eq!(
            m,
            format!("bad count `{bad}` after `at least`: expected a whole number in decimal digits, such as `at least 2`"),
        );
        assert_eq!(lc, (1, 26), "{bad}");
    }
    for big in [
        "65536",
        "99999",
        "100000",
        "4294967296",
        "18446744073709551616",
    ] {
        let (m, lc) = err(&format!("rule x: AL_N(B, at most {big} R)"));
        assert_eq!(
            m,
            format!("count `{big}` after `at most` is too large: expected a whole number from 0 to 65535"),
        );
        assert_eq!(lc, (1, 25));
    }
    // Missing.
    let (m, lc) = err("rule x: AL_N(B, at least R)");
    assert_eq!(m, "expected a count (a whole number such as 2), found `R`");
    assert_eq!(lc, (1, 26));
    let (m, _) = err("rule x: at most : AL_N(B, R)");
    assert_eq!(m, "expected a count (a whole number such as 2), found `:`");
    // Ten thousand digits: the limit error, shortened, no overflow.
    let src = format!("rule x: AL_N(B, at least 1{} R)", "0".repeat(9_999));
    let (m, lc) = err(&src);
    assert_eq!(
        m,
        "count `10000000000000000000…` (10000 digits) after `at least` is too large: expected a whole number from 0 to 65535"
    );
    assert_eq!(lc, (1, 26));
    // Leading zeros do not make a small count large.
    let src = format!("rule x: AL_N(B, at least {}7 R)", "0".repeat(10_000));
    assert_eq!(formula(&src), atq("AL_N", "B", Quant::AtLeast(7), "R"));
}

#[test]
fn all_sixteen_relations_take_every_quantifier() {
    for r in Relation::ALL {
        for (q, text) in [
            (Quant::Every, "every"),
            (Quant::Some, "some"),
            (Quant::No, "no"),
            (Quant::AtLeast(4), "at least 4"),
            (Quant::AtMost(5), "at most 5"),
        ] {
            let f = formula(&format!("rule x: {}(B, {text} G)", r.name()));
            assert_eq!(
                f,
                Formula::Atom(Atom::quantified(r, "B", q, Target::Class("G".into())))
            );
            let printed = print_formula(&f);
            if q == r.default_quant() {
                assert_eq!(printed, format!("{}(B, G)", r.name()));
            } else {
                assert_eq!(printed, format!("{}(B, {text} G)", r.name()));
            }
        }
    }
}

// ---- semantic checks ----------------------------------------------------

#[test]
fn mixed_subjects_error() {
    let (m, lc) = err("rule a: DR_N(B, R) & (DR_S(B, R) | !DR_S(G, R))");
    assert_eq!(
        m,
        "rule `a` mixes subject classes: this atom is about `G`, but the rule's first atom is about `B`"
    );
    assert_eq!(lc, (1, 37));
}

#[test]
fn duplicate_names_error() {
    let (m, lc) = err("rule a: DR_N(B, R)\n\nrule b: DR_N(B, R)\nrule a: DR_S(B, R)\n");
    assert_eq!(
        m,
        "duplicate rule name `a`: it is already defined on line 1"
    );
    assert_eq!(lc, (4, 6));
}

#[test]
fn several_diagnostics_collected() {
    let src = "rule a p 2: DR_N(B, R)\nrule b: XX(B, R)\nrule b: DR_N(B, R) & DR_N(C, R)\n";
    let e = parse_rules(src).unwrap_err();
    assert_eq!(e.diagnostics.len(), 4);
    let lcs: Vec<_> = e.diagnostics.iter().map(|d| d.line_col(src)).collect();
    assert_eq!(lcs, [(1, 10), (2, 9), (3, 6), (3, 22)]);
}

#[test]
fn scope_subject_mismatch_error() {
    let (m, lc) = err("rule a: at least 2 G: FL_N(G, G) | !(AL_S(G, *) & FL_S(B, G))");
    assert_eq!(
        m,
        "rule `a` is about `G` (`at least 2 G:`), but this atom is about `B`: expected every atom's subject to be `G`"
    );
    assert_eq!(lc, (1, 51));
    // Every atom about another class: the first one is reported, once.
    let e = parse_rules("rule a: no G: FL_N(B, G) & FL_S(B, G)").unwrap_err();
    assert_eq!(e.diagnostics.len(), 1);
    assert_eq!(e.line_col("rule a: no G: FL_N(B, G) & FL_S(B, G)"), (1, 15));
    // `every A:` fixes the subject too.
    let (m, _) = err("rule a: every G: FL_N(B, G)");
    assert!(m.starts_with("rule `a` is about `G` (`every G:`)"), "{m}");
    // Without a scope the first edition's check applies.
    let (m, _) = err("rule a: FL_N(G, G) & FL_N(B, G)");
    assert!(m.starts_with("rule `a` mixes subject classes"), "{m}");
}

#[test]
fn second_edition_diagnostics_collected() {
    let src = "\
rule a: EC_E(B, no @w) & DR_N(B, at least 1.5 G)
rule b: some *: DR_N(@x, R)
rule c: at most 70000 G: FL_N(G, G)
rule d: some G: FL_N(G, G) & FL_N(R, G)
";
    let e = parse_rules(src).unwrap_err();
    let got: Vec<_> = e
        .diagnostics
        .iter()
        .map(|d| (d.line_col(src), d.message.split(':').next().unwrap_or("")))
        .collect();
    assert_eq!(
        got,
        [
            ((1, 17), "quantifier `no` before landmark `@w`"),
            ((1, 43), "bad count `1.5` after `at least`"),
            ((2, 14), "expected a class name after `some`, found `*`"),
            ((2, 22), "expected a class name, found `@x`"),
            ((3, 17), "count `70000` after `at most` is too large"),
            ((4, 30), "rule `d` is about `G` (`some G"),
        ]
    );
}

fn scene_rw() -> Scene {
    Scene::from_json(
        r#"{"space":{"width":100,"height":100},"objects":[
            {"class":"R","x":0,"y":0,"width":10,"height":10},
            {"class":"W","x":20,"y":0,"width":10,"height":10}]}"#,
    )
    .unwrap()
}

#[test]
fn check_classes_accepts_known_and_star() {
    let rs = ok("rule a: DR_N(R, W) | EC_E(R, *) & !EC_N(R, R)");
    assert!(check_classes(&rs, &scene_rw()).is_ok());
}

#[test]
fn check_classes_rejects_unknown() {
    let src = "rule a: DR_N(R, W)\nrule q: EC_E(R, *) & DR_S(R, Q)";
    let rs = ok(src);
    let e = check_classes(&rs, &scene_rw()).unwrap_err();
    assert_eq!(e.diagnostics.len(), 1);
    assert_eq!(
        e.diagnostics[0].message,
        "unknown class `Q` in rule `q`: the scene has classes R, W"
    );
    assert_eq!(e.line_col(src), (2, 22));
}

fn scene_walls() -> Scene {
    // Ids as written, the docs/scenes.md#fields default `<class><index>` (W1, R4), an id that is
    // no identifier (`w-3`) and a movable object.
    Scene::from_json(
        r#"{"space":{"width":100,"height":100},"objects":[
            {"id":"w_west","class":"W","x":0,"y":0,"width":10,"height":100,"fixed":true},
            {"class":"W","x":90,"y":0,"width":10,"height":100,"fixed":true},
            {"id":"w-3","class":"W","x":10,"y":0,"width":80,"height":10,"fixed":true},
            {"id":"r1","class":"R","x":20,"y":20,"width":10,"height":10},
            {"class":"R","width":10,"height":10}]}"#,
    )
    .unwrap()
}

#[test]
fn check_landmarks_accepts_fixed_objects() {
    let rs = ok("rule a: some R: EC_E(R, @w_west) | !DR_W(R, @W1)\nrule b: DR_N(R, R)");
    assert!(check_landmarks(&rs, &scene_walls()).is_ok());
    // No landmarks: always fine, even without fixed objects.
    assert!(check_landmarks(&ok(PILOT), &scene_rw()).is_ok());
}

#[test]
fn check_landmarks_rejects_unknown_and_movable() {
    let src = "rule a: EC_E(R, @w_west)\nrule b: FL_N(R, G) & (EC_W(R, @w_east) | EC_N(R, @r1))\n";
    let rs = ok(src);
    let e = check_landmarks(&rs, &scene_walls()).unwrap_err();
    let got: Vec<_> = e
        .diagnostics
        .iter()
        .map(|d| (d.line_col(src), d.message.as_str()))
        .collect();
    assert_eq!(
        got,
        [
            (
                (2, 23),
                "unknown landmark `@w_east` in rule `b`: expected the id of a fixed object; the scene's fixed objects are w_west, W1"
            ),
            (
                (2, 42),
                "landmark `@r1` in rule `b` is not a fixed object: expected the id of a fixed object; the scene's fixed objects are w_west, W1"
            ),
        ]
    );
    // The default id of a movable object is not a landmark either.
    let e = check_landmarks(&ok("rule a: DR_N(R, @R4)"), &scene_walls()).unwrap_err();
    assert!(e.diagnostics[0]
        .message
        .starts_with("landmark `@R4` in rule `a` is not a fixed object"));
}

#[test]
fn check_landmarks_without_fixed_objects() {
    let rs = ok("rule a: no R: EC_E(R, @W9)");
    let e = check_landmarks(&rs, &scene_rw()).unwrap_err();
    assert_eq!(
        e.diagnostics[0].message,
        "unknown landmark `@W9` in rule `a`: expected the id of a fixed object; the scene has no fixed objects that can be landmarks"
    );
    assert_eq!(e.line_col("rule a: no R: EC_E(R, @W9)"), (1, 15));
    // `W1` (the default id of scene_rw's wall) is there but movable.
    let e = check_landmarks(&ok("rule a: EC_E(R, @W1)"), &scene_rw()).unwrap_err();
    assert_eq!(
        e.diagnostics[0].message,
        "landmark `@W1` in rule `a` is not a fixed object: expected the id of a fixed object; the scene has no fixed objects that can be landmarks"
    );
    // An object whose id is not an identifier cannot be a landmark: it is
    // not listed.
    let e = check_landmarks(&ok("rule a: EC_E(R, @w_3)"), &scene_walls()).unwrap_err();
    assert!(!e.diagnostics[0].message.contains("w-3"));
}

#[test]
fn check_landmarks_in_code_built_rules() {
    // Rules without an origin are reported at the start of the text.
    let rule = Rule::new(
        "code",
        Formula::Atom(Atom::new(
            rel("EC_E"),
            "R",
            Target::Landmark("nowhere".into()),
        )),
    );
    let e = check_landmarks(&RuleSet::new(vec![rule]), &scene_walls()).unwrap_err();
    assert_eq!(e.diagnostics[0].span, Span::new(0, 0));
    assert!(e.diagnostics[0]
        .message
        .contains("`@nowhere` in rule `code`"));
}

#[test]
fn render_unknown_landmark() {
    let src = "rule a: some R: EC_E(R, @w_east)\n";
    let text = check_landmarks(&ok(src), &scene_walls())
        .unwrap_err()
        .render("x.rcc", src, false);
    golden("unknown_landmark", &text);
}

// ---- rendered diagnostics (exact text) ---------------------------------

/// Compare a rendered diagnostic with `tests/fixtures/diagnostics/NAME.txt`;
/// `RCCPACK_BLESS=1` rewrites the file instead (only on purpose: the text is
/// what users see).
fn golden(name: &str, actual: &str) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/diagnostics")
        .join(format!("{name}.txt"));
    if std::env::var_os("RCCPACK_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, actual).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (RCCPACK_BLESS=1 writes it)", path.display()));
    assert_eq!(actual, expected, "{} differs", path.display());
}

fn render(src: &str) -> String {
    parse_rules(src).unwrap_err().render("x.rcc", src, false)
}

#[test]
fn render_unknown_relation() {
    golden("unknown_relation", &render("rule a: DR_X(B, R)\n"));
}

#[test]
fn render_mixed_subjects() {
    golden(
        "mixed_subjects",
        &render("rule a: DR_N(B, R) & DR_S(G, R)\n"),
    );
}

#[test]
fn render_missing_colon() {
    golden("missing_colon", &render("rule a DR_N(B, R)\n"));
}

#[test]
fn render_bad_p() {
    golden("bad_p", &render("rule a p 1.5: DR_N(B, R)\n"));
}

#[test]
fn render_duplicate_name() {
    golden(
        "duplicate_name",
        &render("rule a: DR_N(B, R)\nrule a: DR_S(B, R)\n"),
    );
}

#[test]
fn render_unknown_class() {
    let scene = Scene::from_json(
        r#"{"space":{"width":100,"height":100},"objects":[{"class":"R","x":0,"y":0,"width":10,"height":10},{"class":"W","x":20,"y":0,"width":10,"height":10}]}"#,
    )
    .unwrap();
    let src = "rule a: DR_N(B, R)\nrule b: DR_N(R, Q)\n";
    let rs = ok(src);
    let text = check_classes(&rs, &scene)
        .unwrap_err()
        .render("x.rcc", src, false);
    golden("unknown_class", &text);
}

#[test]
fn render_color_and_unicode_columns() {
    // Columns count characters; snippets survive non-ASCII text before the span.
    let src = "# héhé ünïcødé\nrule a: DR_N(B, R) €\n";
    let e = parse_rules(src).unwrap_err();
    assert_eq!(e.line_col(src), (2, 20));
    let text = e.render("u.rcc", src, false);
    assert!(text.contains("u.rcc:2:20"), "{text}");
    assert!(text.contains("rule a: DR_N(B, R) €"), "{text}");
    let src = "rule é: DR_N(B, R)";
    let e = parse_rules(src).unwrap_err();
    assert_eq!(e.diagnostics[0].message, "expected a rule name, found `é`");
    let plain = e.render("f.rcc", src, false);
    assert!(plain.contains("f.rcc:1:6"), "{plain}");
    let colored = e.render("f.rcc", src, true);
    assert!(colored.contains('\u{1b}'), "{colored}");
    assert!(!plain.contains('\u{1b}'), "{plain}");
}

#[test]
fn render_long_line_falls_back_to_plain() {
    let src = format!("rule a: {}XX(B, R)\n", "DR_N(B, R) | ".repeat(2000));
    let e = parse_rules(&src).unwrap_err();
    let text = e.render("big.rcc", &src, false);
    assert_eq!(
        text,
        "error: big.rcc:1:26009: unknown relation `XX`: expected one of DR_N, DR_S, DR_E, DR_W, EC_N, EC_S, EC_E, EC_W, FL_N, FL_S, FL_E, FL_W, AL_N, AL_S, AL_E, AL_W\n"
    );
}

#[test]
fn render_quantified_landmark() {
    golden(
        "quantified_landmark",
        &render("rule a: EC_E(B, some @w_west)\n"),
    );
}

#[test]
fn render_bad_count() {
    golden("bad_count", &render("rule a: DR_N(B, at least 2.0 G)\n"));
}

#[test]
fn render_count_too_large() {
    golden(
        "count_too_large",
        &render("rule a: DR_N(B, at most 65536 G)\n"),
    );
}

#[test]
fn render_missing_count() {
    golden("missing_count", &render("rule a: DR_N(B, at least G)\n"));
}

#[test]
fn render_scope_subject_mismatch() {
    golden(
        "scope_subject_mismatch",
        &render("rule a: some G: FL_N(G, G) & FL_N(B, G)\n"),
    );
}

#[test]
fn render_star_subject() {
    golden("star_subject", &render("rule a: DR_N(*, R)\n"));
}

#[test]
fn render_landmark_subject() {
    golden("landmark_subject", &render("rule a: DR_N(@w, R)\n"));
}

#[test]
fn render_star_scope_subject() {
    golden(
        "star_scope_subject",
        &render("rule a: some *: DR_N(B, R)\n"),
    );
}

#[test]
fn render_landmark_scope_subject() {
    golden(
        "landmark_scope_subject",
        &render("rule a: no @w: DR_N(B, R)\n"),
    );
}

#[test]
fn render_landmark_space() {
    golden("landmark_space", &render("rule a: DR_N(B, @ w)\n"));
}

#[test]
fn render_ten_thousand_digit_count_falls_back_to_plain() {
    let src = format!("rule a: DR_N(B, at least 9{} G)\n", "9".repeat(9_999));
    assert_eq!(
        render(&src),
        "error: x.rcc:1:26: count `99999999999999999999…` (10000 digits) after `at least` is too large: expected a whole number from 0 to 65535\n"
    );
}

// ---- depth and size limits -----------------------------------------------

#[test]
fn deep_parentheses_are_an_error() {
    let src = format!(
        "rule a: {}DR_N(B, R){}",
        "(".repeat(10_000),
        ")".repeat(10_000)
    );
    let (m, lc) = err(&src);
    assert!(m.starts_with("formula nested too deeply"), "{m}");
    // The atom's own `(` counts in the raw scan that runs before pest.
    assert_eq!(lc, (1, 9 + 257));
}

#[test]
fn many_negations_are_an_error() {
    let src = format!("rule a: {}DR_N(B, R)", "!".repeat(100_000));
    let (m, lc) = err(&src);
    assert!(m.starts_with("formula nested too deeply"), "{m}");
    assert_eq!(lc, (1, 9 + 256));
    let src = format!("rule a: {}DR_N(B, R)", "not ".repeat(50_000));
    assert!(parse_rules(&src).is_err());
    // Mixed `!(` chains count both.
    let src = format!("rule a: {}DR_N(B, R){}", "!(".repeat(200), ")".repeat(200));
    assert!(parse_rules(&src).is_err());
}

#[test]
fn depth_limit_boundary() {
    let src = format!("rule a: {}DR_N(B, R){}", "(".repeat(256), ")".repeat(256));
    assert_eq!(formula(&src), at("DR_N", "B", "R"));
    let src = format!("rule a: {}DR_N(B, R)", "!".repeat(256));
    assert_eq!(formula(&src).depth(), 257);
    // Parentheses in comments do not count.
    let src = format!("# {}\nrule a: DR_N(B, R)", "(".repeat(1000));
    ok(&src);
}

#[test]
fn wide_formulas_are_fine() {
    let src = format!(
        "rule a: DR_N(B, R){}",
        " | DR_S(B, R) & EC_E(B, *)".repeat(20_000)
    );
    let f = formula(&src);
    assert_eq!(f.atoms().len(), 40_001);
}

// ---- printer -------------------------------------------------------------

#[test]
fn printer_minimal_parentheses() {
    let cases = [
        "rule a: DR_N(B, R) | DR_S(B, R) & EC_E(B, *)\n",
        "rule a: (DR_N(B, R) | DR_S(B, R)) & EC_E(B, *)\n",
        "rule a: !(DR_N(B, R) & DR_S(B, R)) | !!EC_E(B, *)\n",
        "rule a weight 2.5: !DR_N(B, R)\n",
        "rule a p 1e-8: DR_N(B, R)\n",
        "rule a hard: DR_N(B, R)\n",
    ];
    for c in cases {
        assert_eq!(print_rules(&ok(c)), c);
    }
    assert_eq!(
        print_rules(&ok("rule a weight 1.0: DR_N(B, R)")),
        "rule a: DR_N(B, R)\n"
    );
}

#[test]
fn printer_comments_and_wrapping() {
    let mut rs = ok(PILOT);
    rs.rules[0].comments = vec!["learned from 3 demos".into(), "p = 0.01".into()];
    let text = print_rules(&rs);
    assert!(text
        .starts_with("# learned from 3 demos\n# p = 0.01\nrule blue_north_of_red: DR_N(B, R)\n"));
    assert!(
        text.contains("\n                   | EC_W(B, *) & EC_S(B, *)\n"),
        "{text}"
    );
    assert!(ok(&text).same_rules(&rs));
}

#[test]
fn format_number_examples() {
    assert_eq!(format_number(1.0), "1");
    assert_eq!(format_number(2.5), "2.5");
    assert_eq!(format_number(1e-8), "1e-8");
    assert_eq!(format_number(1e-300), "1e-300");
    assert_eq!(format_number(1e15), "1e15");
    assert_eq!(format_number(0.0001), "0.0001");
}

// ---- properties ----------------------------------------------------------

use rccpack::sample::strategy::{formula_strategy, ruleset_strategy};

fn mutation_strategy() -> impl Strategy<Value = Vec<(u8, usize, char)>> {
    prop::collection::vec(
        (
            0u8..3,
            any::<usize>(),
            prop_oneof![
                any::<char>(),
                prop::sample::select(vec![
                    '(', ')', '!', '&', '|', '\n', ':', ',', '*', '#', ' ', 'e', '9', '.', '@',
                    '0', '+', '-', '_'
                ])
            ],
        ),
        1..8,
    )
}

fn mutate(src: &str, muts: &[(u8, usize, char)]) -> String {
    let mut chars: Vec<char> = src.chars().collect();
    for &(op, at, c) in muts {
        let i = at % (chars.len() + 1);
        match op {
            0 => chars.insert(i, c),
            1 if i < chars.len() => {
                chars.remove(i);
            }
            _ if i < chars.len() => chars[i] = c,
            _ => chars.push(c),
        }
    }
    chars.into_iter().collect()
}

fn no_panic(src: &str) {
    match parse_rules(src) {
        Ok(rs) => {
            // Whatever parses must print and re-parse to the same rules.
            let again = parse_rules(&print_rules(&rs)).expect("printed rules re-parse");
            assert!(again.same_rules(&rs));
        }
        Err(e) => {
            assert!(!e.diagnostics.is_empty());
            let text = e.render("m.rcc", src, false);
            assert!(text.contains("m.rcc:"), "{text}");
        }
    }
}

proptest! {
    #[test]
    fn formulas_print_and_reparse(f in formula_strategy()) {
        let src = format!("rule x: {}", print_formula(&f));
        let back = parse_rules(&src).map_err(|e| TestCaseError::fail(e.render("f.rcc", &src, false)))?;
        prop_assert_eq!(&back.rules[0].formula, &f);
    }

    #[test]
    fn round_trip_print_parse(rs in ruleset_strategy()) {
        let text = print_rules(&rs);
        let back = parse_rules(&text).map_err(|e| TestCaseError::fail(e.render("p.rcc", &text, false)))?;
        prop_assert!(back.same_rules(&rs), "{}\n{:?}\n{:?}", text, rs, back);
    }

    #[test]
    fn format_number_round_trips(v in any::<f64>().prop_filter("finite", |v| v.is_finite())) {
        let s = format_number(v);
        prop_assert_eq!(s.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{}", s);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn no_panic_on_arbitrary_strings(s in any::<String>()) {
        no_panic(&s);
    }

    #[test]
    fn no_panic_on_rcc_like_strings(s in "(rule|[a-zA-Z_]{1,6}|[ \t\n():,*!&|#.0-9e@+-]|DR_N|EC_W|FL_S|AL_E|weight|p|hard|every|some|no|at|least|most|at least|at most|some A:|at least 2 G:|@w_west|[0-9]{1,7}| ){0,40}") {
        no_panic(&s);
    }

    #[test]
    fn no_panic_on_mutated_pilot(muts in mutation_strategy()) {
        no_panic(&mutate(PILOT, &muts));
    }

    #[test]
    fn no_panic_on_mutated_second_edition(muts in mutation_strategy()) {
        no_panic(&mutate(SECOND, &muts));
    }

    #[test]
    fn no_panic_on_second_edition_atoms(
        q in "(every|some|no|at least|at most|at|least|most|)",
        k in "([0-9]{0,8}|[+-]?[0-9]*[.eE]?[+-]?[0-9]*|[0-9]{300})",
        t in "(@?[a-z_]{0,3}|\\*|@|@@|[0-9]{0,2})",
        s in "(some|no|every|at least|at most|)",
        c in "([A-Z]{0,2}|\\*|@w|no|at)",
    ) {
        no_panic(&format!("rule x: {s} {c}: EC_N({c}, {q} {k} {t})"));
        no_panic(&format!("rule x: {q} {k} {c}: EC_N({c}, {t})"));
    }
}

/// Every diagnostic carries a kind code can match; a duplicate name points
/// at the first definition too.
#[test]
fn diagnostics_have_kinds() {
    let kind = |src: &str| parse_rules(src).unwrap_err().diagnostics[0].kind;
    assert_eq!(
        kind("rule a: DR_X(B, R)\n"),
        DiagnosticKind::UnknownRelation
    );
    assert_eq!(kind("rule a DR_N(B, R)\n"), DiagnosticKind::Syntax);
    assert_eq!(
        kind("rule a p 1.5: DR_N(B, R)\n"),
        DiagnosticKind::BadProbability
    );
    assert_eq!(
        kind("rule a weight 0: DR_N(B, R)\n"),
        DiagnosticKind::BadWeight
    );
    assert_eq!(
        kind("rule a: DR_N(B, at least 2.0 G)\n"),
        DiagnosticKind::BadCount
    );
    assert_eq!(
        kind("rule a: DR_N(B, R) & DR_S(G, R)\n"),
        DiagnosticKind::MixedSubjects
    );
    assert_eq!(
        kind("rule a: EC_E(B, some @w)\n"),
        DiagnosticKind::LandmarkQuantifier
    );
    let nested = format!("rule a: {}DR_N(B, R)\n", "!".repeat(10_000));
    assert_eq!(kind(&nested), DiagnosticKind::TooDeep);
    let src = "rule a: DR_N(B, R)\nrule a: DR_S(B, R)\n";
    let d = &parse_rules(src).unwrap_err().diagnostics[0];
    assert_eq!(d.kind, DiagnosticKind::DuplicateName);
    let (first, what) = d.related.clone().expect("the first definition");
    assert_eq!((first.start, what.as_str()), (5, "first defined here"));
    let e = check_classes(&ok("rule a: DR_N(B, R)\n"), &scene_rw()).unwrap_err();
    assert!(e
        .diagnostics
        .iter()
        .all(|d| d.kind == DiagnosticKind::UnknownClass));
    let e = check_landmarks(&ok("rule a: some R: EC_E(R, @nope)\n"), &scene_walls()).unwrap_err();
    assert_eq!(e.diagnostics[0].kind, DiagnosticKind::UnknownLandmark);
}
