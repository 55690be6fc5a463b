//! The report of `rccpack-bench priors` as markdown: the population, the
//! learning table, the question table, the spurious rules by kind and the
//! targets.

use super::*;

fn frac(k: usize, n: usize) -> String {
    if n == 0 {
        format!("{k}/0")
    } else {
        format!("{k}/{n} ({:.0} %)", 100.0 * k as f64 / n as f64)
    }
}

fn per_task(v: usize, tasks: usize) -> String {
    format!("{:.1}", v as f64 / tasks.max(1) as f64)
}

/// The report as markdown: the population, the learning table, the
/// question table, the spurious rules by kind and the targets.
pub fn table_markdown(r: &PriorsBenchReport) -> String {
    let mut s = String::new();
    population_text(&mut s, r);
    learning_table(&mut s, r);
    ask_table(&mut s, r);
    spurious_kinds_table(&mut s, r);
    targets_text(&mut s, r);
    s
}

fn library_cell(condition: Condition, library: usize) -> String {
    if condition == Condition::Uniform {
        "–".to_string()
    } else {
        library.to_string()
    }
}

fn population_text(s: &mut String, r: &PriorsBenchReport) {
    use std::fmt::Write;
    let c = &r.config;
    let habits = r
        .habits
        .iter()
        .map(|(h, n)| format!("{h} {n}"))
        .collect::<Vec<_>>()
        .join(", ");
    let _ = writeln!(
        s,
        "Population (seed {}): {} library + {} held-out tasks ({} demonstrations each; library 3–5), truth from {} demonstrations, true library {} tasks. Habits of their classes: {habits}.\n",
        c.seed,
        r.library.len(),
        r.held_out.len(),
        c.held_out_demos,
        c.truth_demos,
        c.true_library
    );
}

fn learning_table(s: &mut String, r: &PriorsBenchReport) {
    use std::fmt::Write;
    let tasks = r.held_out.len();
    let _ = writeln!(
        s,
        "| library | condition | recall | rare recall | spurious | spurious/task | learned/task | truth ruled out | left out/task |"
    );
    let _ = writeln!(s, "|---:|---|---:|---:|---:|---:|---:|---:|---:|");
    for row in &r.rows {
        let t = &row.total;
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            library_cell(row.condition, row.library),
            row.condition.name(),
            frac(t.recalled, t.truth),
            frac(t.rare_recalled, t.rare),
            t.spurious,
            per_task(t.spurious, tasks),
            per_task(t.learned, tasks),
            t.truth_ruled_out,
            per_task(t.left_out, tasks),
        );
    }
}

fn ask_table(s: &mut String, r: &PriorsBenchReport) {
    use std::fmt::Write;
    if r.ask.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "\nQuestions with a truth oracle on {} held-out tasks (at most {} per task; a capped task counts the cap):\n",
        r.ask.first().map_or(0, |a| a.per_task.len()),
        r.config.max_questions
    );
    let _ = writeln!(
        s,
        "| library | condition | median questions | questions per task | capped | spurious before → after | recall before → after |"
    );
    let _ = writeln!(s, "|---:|---|---:|---|---:|---|---|");
    for a in &r.ask {
        let qs = a
            .per_task
            .iter()
            .map(|o| o.questions.to_string())
            .collect::<Vec<_>>()
            .join(" ");
        let _ = writeln!(
            s,
            "| {} | {} | {} | {qs} | {} | {} → {} | {} → {} |",
            library_cell(a.condition, a.library),
            a.condition.name(),
            a.median_questions,
            a.capped,
            a.before.spurious,
            a.after.spurious,
            frac(a.before.recalled, a.before.truth),
            frac(a.after.recalled, a.after.truth),
        );
    }
}

fn spurious_kinds_table(s: &mut String, r: &PriorsBenchReport) {
    use std::fmt::Write;
    if r.spurious_kinds.is_empty() {
        return;
    }
    let n = r
        .rows
        .iter()
        .rfind(|x| x.condition == Condition::Learned)
        .map_or(0, |x| x.library);
    let _ = writeln!(
        s,
        "\nSpurious rules by kind (the {SPURIOUS_SHOWN} largest; all in the JSON report), with what the {n}-task library says about the kind:\n"
    );
    let _ = writeln!(
        s,
        "| kind | uniform | learned ({n}) | tasks kept / tasks with a candidate | prior |"
    );
    let _ = writeln!(s, "|---|---:|---:|---:|---:|");
    for k in r.spurious_kinds.iter().take(SPURIOUS_SHOWN) {
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {}/{} | {:.2} |",
            k.kind, k.uniform, k.learned, k.tasks_kept, k.tasks, k.prior
        );
    }
}

fn targets_text(s: &mut String, r: &PriorsBenchReport) {
    use std::fmt::Write;
    if r.targets.is_empty() {
        return;
    }
    let _ = writeln!(s, "\nTargets:\n");
    for t in &r.targets {
        let _ = writeln!(
            s,
            "- {}: {} ({})",
            t.target,
            if t.holds { "holds" } else { "MISSES" },
            t.measured
        );
    }
}
