//! The studio's HTTP API, against the router without a socket.

use axum::body::Body;
use axum::http::{Method, Request, StatusCode};
use http_body_util::BodyExt;
use rccpack::scene::scenes_from_json;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use tower::ServiceExt;

/// A fresh copy of the bundled example in a temporary folder (no demos.json
/// unless `with_demos`).
fn task_dir(tag: &str, with_demos: bool) -> PathBuf {
    let files: &[&str] = if with_demos {
        &["problem.json", "demos.json"]
    } else {
        &["problem.json"]
    };
    crate::support::example_copy(&format!("studio-{tag}"), "box-packing", files)
}

async fn call(
    app: &axum::Router,
    method: Method,
    uri: &str,
    body: impl Into<Body>,
) -> (StatusCode, Value) {
    let req = Request::builder()
        .method(method)
        .uri(uri)
        .header("content-type", "application/json")
        .body(body.into())
        .unwrap();
    let res = app.clone().oneshot(req).await.unwrap();
    let status = res.status();
    let bytes = res.into_body().collect().await.unwrap().to_bytes();
    let v = serde_json::from_slice(&bytes)
        .unwrap_or(Value::String(String::from_utf8_lossy(&bytes).into()));
    (status, v)
}

/// The example's walls plus `blocks` as `(class, x, y)` 20×20 objects.
fn demo(blocks: &[(&str, i64, i64)]) -> Value {
    let problem: Value = serde_json::from_str(
        &std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/box-packing/problem.json"),
        )
        .unwrap(),
    )
    .unwrap();
    let mut objects: Vec<Value> = problem["objects"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|o| o["fixed"] == json!(true))
        .cloned()
        .collect();
    for (i, (c, x, y)) in blocks.iter().enumerate() {
        objects.push(json!({"id": format!("{}{}", c.to_lowercase(), i), "class": c, "x": x, "y": y, "width": 20, "height": 20}));
    }
    json!({"space": problem["space"], "grid": problem["grid"], "objects": objects})
}

fn demos_on_disk(dir: &Path) -> usize {
    scenes_from_json(&std::fs::read_to_string(dir.join("demos.json")).unwrap())
        .unwrap()
        .len()
}

#[tokio::test]
async fn page_and_task() {
    let dir = task_dir("page", false);
    let app = rccpack::studio::router(&dir).unwrap();
    assert_eq!(
        std::fs::read_to_string(dir.join("demos.json"))
            .unwrap()
            .trim(),
        "[]"
    );
    let req = Request::builder().uri("/").body(Body::empty()).unwrap();
    let res = app.clone().oneshot(req).await.unwrap();
    assert_eq!(res.status(), StatusCode::OK);
    assert!(res.headers()["content-type"]
        .to_str()
        .unwrap()
        .starts_with("text/html"));
    let (s, _) = call(&app, Method::GET, "/assets/app.js", Body::empty()).await;
    assert_eq!(s, StatusCode::OK);
    let (s, _) = call(
        &app,
        Method::GET,
        "/assets/..%2Fproblem.json",
        Body::empty(),
    )
    .await;
    assert_eq!(s, StatusCode::NOT_FOUND);
    // Only loopback host names are answered.
    let req = Request::builder()
        .uri("/api/task")
        .header("host", "evil.example:80")
        .body(Body::empty())
        .unwrap();
    assert_eq!(
        app.clone().oneshot(req).await.unwrap().status(),
        StatusCode::FORBIDDEN
    );
    let req = Request::builder()
        .uri("/api/task")
        .header("host", "127.0.0.1:8080")
        .body(Body::empty())
        .unwrap();
    assert_eq!(
        app.clone().oneshot(req).await.unwrap().status(),
        StatusCode::OK
    );
    let (s, task) = call(&app, Method::GET, "/api/task", Body::empty()).await;
    assert_eq!(s, StatusCode::OK);
    let kinds: Vec<&str> = task["kinds"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k["class"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["R", "G", "B"]);
    assert_eq!(task["colours"]["R"], "#d9534f");
    assert_eq!(task["kinds"][0]["count"], 3);
}

#[tokio::test]
async fn save_valid_and_invalid_demonstrations() {
    let dir = task_dir("save", false);
    let app = rccpack::studio::router(&dir).unwrap();
    let good = demo(&[("R", 200, 200), ("R", 220, 200), ("B", 200, 220)]);
    let (s, v) = call(&app, Method::POST, "/api/demos", good.to_string()).await;
    assert_eq!(s, StatusCode::CREATED, "{v}");
    assert_eq!(v["count"], 1);
    assert_eq!(demos_on_disk(&dir), 1);

    // Malformed JSON: 400 with the scene parser's field path.
    let mut bad = good.clone();
    bad["objects"][5]["x"] = json!(12.5);
    let (s, v) = call(&app, Method::POST, "/api/demos", bad.to_string()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert_eq!(v["path"], "objects[5].x");
    assert!(
        v["error"]
            .as_str()
            .unwrap()
            .contains("objects[5].x: invalid type: floating point `12.5`, expected i64"),
        "{v}"
    );
    // Unknown field.
    let mut bad = good.clone();
    bad["objects"][4]["colour"] = json!("red");
    let (s, v) = call(&app, Method::POST, "/api/demos", bad.to_string()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert!(
        v["error"]
            .as_str()
            .unwrap()
            .contains("unknown field `colour`"),
        "{v}"
    );
    // Not JSON at all.
    let (s, v) = call(&app, Method::POST, "/api/demos", "{\"space\": ").await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert!(
        v["error"].as_str().unwrap().starts_with("demonstration: "),
        "{v}"
    );
    // Overlap (the same check as `check`/`score`), names both objects.
    let overlap = demo(&[("R", 200, 200), ("G", 210, 200)]);
    let (s, v) = call(&app, Method::POST, "/api/demos", overlap.to_string()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    let msg = v["error"].as_str().unwrap();
    assert!(msg.contains("r0") && msg.contains("g1"), "{msg}");
    // Out of the space.
    let out = demo(&[("R", 590, 10)]);
    let (s, _) = call(&app, Method::POST, "/api/demos", out.to_string()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    // A moved wall.
    let mut moved = good.clone();
    moved["objects"][0]["x"] = json!(0);
    let (s, v) = call(&app, Method::POST, "/api/demos", moved.to_string()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert!(v["error"].as_str().unwrap().contains("w_south"), "{v}");
    // An unplaced object.
    let mut unplaced = good.clone();
    unplaced["objects"][4].as_object_mut().unwrap().remove("x");
    unplaced["objects"][4].as_object_mut().unwrap().remove("y");
    let (s, v) = call(&app, Method::POST, "/api/demos", unplaced.to_string()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert!(
        v["error"].as_str().unwrap().contains("has no position"),
        "{v}"
    );
    // A kind the problem does not have.
    let odd = demo(&[("Q", 200, 200)]);
    let (s, _) = call(&app, Method::POST, "/api/demos", odd.to_string()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    // Nothing invalid reached the file.
    assert_eq!(demos_on_disk(&dir), 1);

    // Browse, show, delete.
    let (s, v) = call(&app, Method::GET, "/api/demos", Body::empty()).await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(v["count"], 1);
    let (s, v) = call(&app, Method::GET, "/api/demos/0", Body::empty()).await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(v["objects"].as_array().unwrap().len(), 7);
    let (s, _) = call(&app, Method::GET, "/api/demos/1", Body::empty()).await;
    assert_eq!(s, StatusCode::NOT_FOUND);
    // A delete from a page that listed an older file is refused.
    let (_, listed) = call(&app, Method::GET, "/api/demos", Body::empty()).await;
    let (s, v) = call(
        &app,
        Method::DELETE,
        "/api/demos/0?version=0123456789abcdef",
        Body::empty(),
    )
    .await;
    assert_eq!(s, StatusCode::CONFLICT, "{v}");
    assert_eq!(demos_on_disk(&dir), 1);
    let uri = format!(
        "/api/demos/0?version={}",
        listed["version"].as_str().unwrap()
    );
    let (s, v) = call(&app, Method::DELETE, &uri, Body::empty()).await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(v["count"], 0);
    assert_eq!(demos_on_disk(&dir), 0);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn concurrent_saves_lose_nothing() {
    let dir = task_dir("concurrent", false);
    let app = rccpack::studio::router(&dir).unwrap();
    let mut handles = Vec::new();
    for i in 0..24 {
        let app = app.clone();
        handles.push(tokio::spawn(async move {
            let d = demo(&[("R", 200 + 10 * (i % 18), 200), ("B", 200, 300)]);
            call(&app, Method::POST, "/api/demos", d.to_string())
                .await
                .0
        }));
    }
    for h in handles {
        assert_eq!(h.await.unwrap(), StatusCode::CREATED);
    }
    assert_eq!(demos_on_disk(&dir), 24);
    // No temporary file left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty());
}

#[tokio::test]
async fn corrupt_demos_file_is_reported_and_kept() {
    let dir = task_dir("corrupt", false);
    let corrupt = "[{\"space\": {\"width\": 600, \"height\": 600}, \"objects\": [ oops";
    std::fs::write(dir.join("demos.json"), corrupt).unwrap();
    let app = rccpack::studio::router(&dir).unwrap();
    let (s, v) = call(&app, Method::GET, "/api/demos", Body::empty()).await;
    assert_eq!(s, StatusCode::CONFLICT);
    assert!(v["error"].as_str().unwrap().contains("demos.json"), "{v}");
    assert_eq!(v["kind"], "corrupt_demos");
    let good = demo(&[("R", 200, 200)]);
    let (s, _) = call(&app, Method::POST, "/api/demos", good.to_string()).await;
    assert_eq!(s, StatusCode::CONFLICT);
    let (s, _) = call(&app, Method::DELETE, "/api/demos/0", Body::empty()).await;
    assert_eq!(s, StatusCode::CONFLICT);
    assert_eq!(
        std::fs::read_to_string(dir.join("demos.json")).unwrap(),
        corrupt
    );
    // A well-formed file with an invalid scene is corrupt too.
    std::fs::write(dir.join("demos.json"), "{\"not\": \"an array\"}").unwrap();
    let (s, _) = call(&app, Method::POST, "/api/demos", good.to_string()).await;
    assert_eq!(s, StatusCode::CONFLICT);
    assert_eq!(
        std::fs::read_to_string(dir.join("demos.json")).unwrap(),
        "{\"not\": \"an array\"}"
    );
}

#[tokio::test]
async fn oversize_body_is_refused() {
    let dir = task_dir("oversize", false);
    let app = rccpack::studio::router(&dir).unwrap();
    let big = format!("{{\"pad\": \"{}\"}}", "x".repeat(2 << 20));
    let (s, _) = call(&app, Method::POST, "/api/demos", big.clone()).await;
    assert_eq!(s, StatusCode::PAYLOAD_TOO_LARGE);
    let (s, v) = call(&app, Method::PUT, "/api/learned", big).await;
    assert_eq!(s, StatusCode::PAYLOAD_TOO_LARGE);
    // The documented JSON error form, not plain text.
    assert!(v["error"].as_str().unwrap().contains("too large"), "{v}");
    assert_eq!(demos_on_disk(&dir), 0);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn learn_and_save_learned_rules() {
    let dir = task_dir("learn", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/learn",
        json!({"samples": 200}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["source"], "templates");
    let rules = v["rules"].as_array().unwrap();
    assert!(!rules.is_empty());
    let posts: Vec<f64> = rules
        .iter()
        .map(|r| r["posterior"].as_f64().unwrap())
        .collect();
    assert!(
        posts.windows(2).all(|w| w[0] <= w[1]),
        "strongest first: {posts:?}"
    );
    assert!(rules
        .iter()
        .all(|r| !r["english"].as_str().unwrap().is_empty()));
    // Bad parameters: 400/422 with a message, never a panic.
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/learn",
        json!({"samples": "many"}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert_eq!(v["path"], "samples");

    // Save the first two rules.
    let (s, l) = call(&app, Method::GET, "/api/learned", Body::empty()).await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(l["exists"], false);
    let text = format!(
        "{}\n{}{}",
        v_header(&app).await,
        rules[0]["rcc"].as_str().unwrap(),
        rules[1]["rcc"].as_str().unwrap()
    );
    let (s, saved) = call(
        &app,
        Method::PUT,
        "/api/learned",
        json!({"text": text, "base_version": l["version"]}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{saved}");
    assert_eq!(saved["rules"].as_array().unwrap().len(), 2);
    assert_eq!(
        std::fs::read_to_string(dir.join("learned.rcc")).unwrap(),
        text
    );

    // A hand edit on disk: saving over it with the old version is refused.
    let edited = format!("{text}rule mine hard: DR_N(B, R)\n");
    std::fs::write(dir.join("learned.rcc"), &edited).unwrap();
    let (s, v) = call(
        &app,
        Method::PUT,
        "/api/learned",
        json!({"text": text, "base_version": saved["version"]}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::CONFLICT);
    assert_eq!(v["current"]["text"], edited.as_str());
    assert_eq!(
        std::fs::read_to_string(dir.join("learned.rcc")).unwrap(),
        edited
    );
    // With the current version it goes through.
    let (s, _) = call(
        &app,
        Method::PUT,
        "/api/learned",
        json!({"text": text, "base_version": v["current"]["version"]}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK);

    // Invalid rules are refused with the CLI's located diagnostic.
    let (s, v) = call(
        &app,
        Method::PUT,
        "/api/learned",
        json!({"text": "rule x: DR_N(B, Q)\n", "base_version": "absent"}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert!(
        v["error"].as_str().unwrap().contains("learned.rcc:1:"),
        "{v}"
    );
}

async fn v_header(app: &axum::Router) -> String {
    let (_, v) = call(
        app,
        Method::POST,
        "/api/learn",
        json!({"samples": 200}).to_string(),
    )
    .await;
    v["header"].as_str().unwrap().to_string()
}

#[tokio::test]
async fn learn_without_demonstrations_is_a_clear_error() {
    let dir = task_dir("learn-empty", false);
    let app = rccpack::studio::router(&dir).unwrap();
    let (s, v) = call(&app, Method::POST, "/api/learn", Body::empty()).await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY);
    assert!(
        v["error"].as_str().unwrap().contains("no demonstrations"),
        "{v}"
    );
}

#[test]
fn missing_or_bad_problem_is_an_error() {
    let dir = task_dir("noproblem", false);
    std::fs::remove_file(dir.join("problem.json")).unwrap();
    let e = rccpack::studio::router(&dir).unwrap_err().to_string();
    assert!(e.contains("problem.json"), "{e}");
    std::fs::write(
        dir.join("problem.json"),
        "{\"space\": {\"width\": 1.5, \"height\": 3}, \"objects\": []}",
    )
    .unwrap();
    let e = rccpack::studio::router(&dir).unwrap_err().to_string();
    assert!(e.contains("space.width"), "{e}");
}

async fn wait_job(app: &axum::Router, job: &Value) -> Value {
    for _ in 0..1200 {
        let (s, v) = call(
            app,
            Method::GET,
            &format!("/api/synth/{job}"),
            Body::empty(),
        )
        .await;
        assert_eq!(s, StatusCode::OK, "{v}");
        if v["state"] != "running" {
            return v;
        }
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
    panic!("synthesis job {job} did not finish");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn synth_on_the_bundled_example() {
    let dir = task_dir("synth", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let pilot = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/box-packing/pilot.rcc"),
    )
    .unwrap();
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/synth",
        json!({"rules": pilot, "time_limit": 60}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::ACCEPTED, "{v}");
    let done = wait_job(&app, &v["job"]).await;
    assert_eq!(done["state"], "done", "{done}");
    let r = &done["result"];
    assert_eq!(r["status"], "optimal");
    assert_eq!(r["score"], 1.0);
    assert_eq!(r["evaluation"]["rules"].as_array().unwrap().len(), 12);
    let scene = rccpack::scene::Scene::from_json(&r["scene"].to_string()).unwrap();
    assert!(scene.is_complete());
    assert_eq!(scene.objects.len(), 13);
    // The saved demonstrations are the like-scenes by default (docs/guide.md#layouts-like-the-demonstrations).
    let demos =
        rccpack::scene::scenes_from_json(&std::fs::read_to_string(dir.join("demos.json")).unwrap())
            .unwrap();
    let problem = rccpack::scene::Scene::from_json(
        &std::fs::read_to_string(dir.join("problem.json")).unwrap(),
    )
    .unwrap();
    let cost = rccpack::resemblance::ResemblanceTarget::new(&demos).cost(&problem, &scene);
    assert_eq!(r["resemblance"]["cost"], cost, "{r}");
    assert_eq!(r["resemblance"]["proven"], true);
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/synth",
        json!({"rules": pilot, "like": false}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::ACCEPTED, "{v}");
    let done = wait_job(&app, &v["job"]).await;
    assert!(done["result"]["resemblance"].is_null(), "{done}");
    assert_eq!(done["result"]["score"], 1.0);

    // Bad rules: the located diagnostic; bad limit: field path.
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/synth",
        json!({"rules": "rule x: DR_N(B R)\n"}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert!(
        v["error"].as_str().unwrap().contains("chosen rules:1:"),
        "{v}"
    );
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/synth",
        json!({"rules": pilot, "time_limit": -1}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert_eq!(v["path"], "time_limit");
    let (s, _) = call(&app, Method::GET, "/api/synth/999", Body::empty()).await;
    assert_eq!(s, StatusCode::NOT_FOUND);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn synth_can_be_cancelled() {
    let dir = task_dir("cancel", true);
    let app = rccpack::studio::router(&dir).unwrap();
    // Templates-style rules that are hard to prove optimal; cancel at once.
    let rules = "rule a: EC_N(R, G) | EC_E(R, B)\nrule b: EC_W(G, R) & EC_N(G, *)\nrule c: DR_S(B, G) | EC_S(B, R)\n";
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/synth",
        json!({"rules": rules, "time_limit": 120}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::ACCEPTED, "{v}");
    let (s, c) = call(
        &app,
        Method::POST,
        &format!("/api/synth/{}/cancel", v["job"]),
        Body::empty(),
    )
    .await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(c["cancelled"], true);
    let started = std::time::Instant::now();
    let done = wait_job(&app, &v["job"]).await;
    assert!(started.elapsed().as_secs() < 30, "cancel stops the search");
    eprintln!(
        "cancelled job ended: {} after {:?}",
        done["result"]["status"],
        started.elapsed()
    );
    assert_eq!(done["cancelled"], true);
    assert_eq!(done["state"], "done", "{done}");
}

/// The studio's `samples` has the documented upper bound (a huge value
/// would run until killed), and `time_limit` goes through the
/// shared parser; both answer 400 naming the field.
#[tokio::test]
async fn learn_samples_and_synth_time_limit_are_bounded() {
    let dir = task_dir("bounds", true);
    let app = rccpack::studio::router(&dir).unwrap();
    for n in [
        json!(0),
        json!(1_000_001u64),
        json!(1_000_000_000_000_000u64),
        json!(u64::MAX),
    ] {
        let (s, v) = call(
            &app,
            Method::POST,
            "/api/learn",
            json!({"samples": n}).to_string(),
        )
        .await;
        assert_eq!(s, StatusCode::BAD_REQUEST, "{n}: {v}");
        assert_eq!(v["path"], "samples");
        assert!(
            v["error"].as_str().unwrap().contains("from 1 to 1000000"),
            "{v}"
        );
    }
    for t in [json!(0), json!(600.5), json!(1e20), json!(-1)] {
        let (s, v) = call(
            &app,
            Method::POST,
            "/api/synth",
            json!({"rules": "", "time_limit": t}).to_string(),
        )
        .await;
        assert_eq!(s, StatusCode::BAD_REQUEST, "{t}: {v}");
        assert_eq!(v["path"], "time_limit");
    }
}

// ---- Check rules (docs/guide.md#questions) --------------------------------------------------------

fn answers_on_disk(dir: &Path) -> Vec<Value> {
    let v: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("answers.json")).unwrap()).unwrap();
    v["answers"].as_array().unwrap().clone()
}

/// The next question of a session that asks about one rule per question
/// (`groups: false`: these tests check what one answer does to one rule).
async fn next_question(app: &axum::Router) -> Value {
    next_question_with(app, json!({"samples": 200, "groups": false})).await
}

async fn next_question_with(app: &axum::Router, body: Value) -> Value {
    let (s, v) = call(app, Method::POST, "/api/ask/next", body.to_string()).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    v
}

/// With group questions (the default), the first question of the bundled
/// example breaks a group of rules; "not acceptable" confirms none of them
/// and the next question is about part of that group; "acceptable" drops
/// all the rules it breaks. The page gets each rule's English reading.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ask_group_questions_narrow_a_rejected_group() {
    let dir = task_dir("ask-groups", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let v = next_question_with(&app, json!({"samples": 200})).await;
    let q1 = v["question"].clone();
    let group: Vec<String> = q1["group"]
        .as_array()
        .unwrap_or_else(|| panic!("a group question: {q1}"))
        .iter()
        .map(|g| {
            assert!(!g["english"].as_str().unwrap().is_empty(), "{g}");
            g["rule"].as_str().unwrap().to_string()
        })
        .collect();
    assert!(group.len() >= 2, "{q1}");
    assert_eq!(q1["rule"], group[0].as_str());
    let v = answer(&app, &q1["rule"], false).await;
    assert_eq!(v["progress"]["confirmed"], 0, "{v}");
    assert_eq!(v["progress"]["grouped"], 1, "{v}");
    assert_eq!(answers_on_disk(&dir)[0]["group"], json!(group));
    let q2 = next_question_with(&app, json!({"samples": 200})).await["question"].clone();
    let asked: Vec<String> = match q2["group"].as_array() {
        Some(g) => g
            .iter()
            .map(|g| g["rule"].as_str().unwrap().to_string())
            .collect(),
        None => vec![q2["rule"].as_str().unwrap().to_string()],
    };
    assert!(asked.len() < group.len(), "{q2}");
    assert!(
        asked.iter().all(|r| group.contains(r)),
        "{asked:?} in {group:?}"
    );
    let v = answer(&app, &q2["rule"], true).await;
    assert_eq!(v["progress"]["dropped"], asked.len(), "{v}");
    let rcc = std::fs::read_to_string(dir.join("learned.rcc")).unwrap();
    for r in &asked {
        assert!(
            !rcc.contains(&format!("rule {r}:")) && !rcc.contains(&format!("rule {r} ")),
            "{r} dropped"
        );
    }
    if group.len() == 2 {
        // The one left of the rejected pair is meant: confirmed without a
        // question.
        assert_eq!(v["progress"]["deduced"], 1, "{v}");
        assert_eq!(v["progress"]["confirmed"], 1, "{v}");
    }
}

async fn answer(app: &axum::Router, rule: &Value, accepted: bool) -> Value {
    let (s, v) = call(
        app,
        Method::POST,
        "/api/ask/answer",
        json!({"rule": rule, "accepted": accepted}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    v
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ask_next_returns_a_probe_question() {
    let dir = task_dir("ask-next", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let v = next_question(&app).await;
    let q = &v["question"];
    assert!(q.is_object(), "{v}");
    assert_eq!(q["number"], 1);
    assert!(!q["rule"].as_str().unwrap().is_empty());
    assert!(!q["statement"].as_str().unwrap().is_empty());
    assert!(!q["english"].as_str().unwrap().is_empty());
    assert!(q["broken"].is_array());
    // The probe is a complete layout of the problem: every object placed.
    let objects = q["scene"]["objects"].as_array().unwrap();
    assert_eq!(objects.len(), 13);
    assert!(objects.iter().all(|o| o["x"].is_i64() && o["y"].is_i64()));
    let ids: Vec<&str> = objects.iter().map(|o| o["id"].as_str().unwrap()).collect();
    for b in q["broken"].as_array().unwrap() {
        assert!(ids.contains(&b.as_str().unwrap()), "{b} in {ids:?}");
    }
    assert_eq!(v["progress"]["asked"], 0);
    assert!(v["progress"]["held"].as_u64().unwrap() > 0);
    // learned.rcc is written at the start, as `rccpack ask` does, and
    // `learned` has the shape of GET /api/learned.
    assert_eq!(v["learned"]["exists"], true);
    assert!(!v["learned"]["rules"].as_array().unwrap().is_empty());
    let (_, l) = call(&app, Method::GET, "/api/learned", Body::empty()).await;
    assert_eq!(l, v["learned"]);
    // Asking again without answering shows the same question.
    let again = next_question(&app).await;
    assert_eq!(again["question"], v["question"]);
    assert!(!dir.join("answers.json").exists());
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ask_answers_are_saved_like_the_command_line() {
    let dir = task_dir("ask-answer", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let n0 = demos_on_disk(&dir);

    // Not like that: the rule is confirmed, demos.json unchanged.
    let q1 = next_question(&app).await["question"].clone();
    let rule1 = q1["rule"].as_str().unwrap().to_string();
    let v = answer(&app, &q1["rule"], false).await;
    assert_eq!(v["progress"]["asked"], 1);
    assert_eq!(v["progress"]["confirmed"], 1);
    assert_eq!(v["progress"]["dropped"], 0);
    assert_eq!(v["answer"]["accepted"], false);
    assert_eq!(demos_on_disk(&dir), n0);
    let answers = answers_on_disk(&dir);
    assert_eq!(answers.len(), 1);
    assert_eq!(answers[0]["rule"], rule1.as_str());
    assert_eq!(answers[0]["accepted"], false);
    assert_eq!(answers[0]["probe"], q1["scene"]);
    let rcc = std::fs::read_to_string(dir.join("learned.rcc")).unwrap();
    let confirmed = format!("# {}\n", rccpack::ask::CONFIRMED);
    let block = rcc
        .split("\n\n")
        .find(|b| b.contains(&format!("rule {rule1} ")) || b.contains(&format!("rule {rule1}:")))
        .unwrap_or_else(|| panic!("rule {rule1} in {rcc}"));
    assert!(block.contains(&confirmed), "{block}");
    assert_eq!(v["learned"]["text"], rcc.as_str());
    // The learned-rules summary marks it.
    let listed = v["learned"]["rules"].as_array().unwrap();
    let r1 = listed.iter().find(|r| r["name"] == rule1.as_str()).unwrap();
    assert_eq!(r1["confirmed"], true);
    assert!(listed.iter().filter(|r| r["confirmed"] == true).count() == 1);

    // The confirmed rule is not asked again. Looks right: the probe joins
    // the demonstrations.
    let q2 = next_question(&app).await["question"].clone();
    assert_ne!(q2["rule"], rule1.as_str());
    assert_eq!(q2["number"], 2);
    let v = answer(&app, &q2["rule"], true).await;
    assert_eq!(v["progress"]["asked"], 2);
    assert_eq!(v["progress"]["dropped"], 1);
    assert_eq!(v["answer"]["demo"], n0);
    assert_eq!(demos_on_disk(&dir), n0 + 1);
    let demos: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("demos.json")).unwrap()).unwrap();
    assert_eq!(demos[n0], q2["scene"]);
    let answers = answers_on_disk(&dir);
    assert_eq!(answers.len(), 2);
    assert_eq!(answers[1]["accepted"], true);
    assert_eq!(answers[1]["demo"], n0);
    // The dropped rule is no longer in learned.rcc; the confirmed one stays.
    let rcc = std::fs::read_to_string(dir.join("learned.rcc")).unwrap();
    let rule2 = q2["rule"].as_str().unwrap();
    assert!(!rcc.contains(&format!("rule {rule2} ")), "{rcc}");
    assert!(rcc.contains(&format!("rule {rule1} ")), "{rcc}");

    // Answering the same question twice: nothing is open about it.
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/ask/answer",
        json!({"rule": q2["rule"], "accepted": true}).to_string(),
    )
    .await;
    assert!(s.is_client_error(), "{s} {v}");
    assert_eq!(answers_on_disk(&dir).len(), 2);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ask_refuses_wrong_rules_and_bad_bodies() {
    let dir = task_dir("ask-bad", true);
    let app = rccpack::studio::router(&dir).unwrap();
    // No question asked yet.
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/ask/answer",
        json!({"rule": "x", "accepted": true}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::CONFLICT, "{v}");
    assert!(
        v["error"].as_str().unwrap().contains("no question is open"),
        "{v}"
    );
    let q = next_question(&app).await["question"].clone();
    // A rule that is not the open question's.
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/ask/answer",
        json!({"rule": "not_the_rule", "accepted": false}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::CONFLICT, "{v}");
    let msg = v["error"].as_str().unwrap();
    assert!(
        msg.contains("not_the_rule") && msg.contains(q["rule"].as_str().unwrap()),
        "{msg}"
    );
    assert_eq!(v["path"], "rule");
    // Bad bodies: 400 naming the field.
    for (body, field) in [
        (
            json!({"rule": q["rule"], "accepted": "yes"}).to_string(),
            "accepted",
        ),
        (json!({"rule": 3, "accepted": true}).to_string(), "rule"),
        (json!({"accepted": true}).to_string(), "rule"),
        (json!({"rule": q["rule"]}).to_string(), "accepted"),
        (
            json!({"rule": q["rule"], "accepted": true, "why": 1}).to_string(),
            "why",
        ),
    ] {
        let (s, v) = call(&app, Method::POST, "/api/ask/answer", body.clone()).await;
        assert_eq!(s, StatusCode::BAD_REQUEST, "{body}: {v}");
        assert!(v["error"].as_str().unwrap().contains(field), "{body}: {v}");
    }
    let (s, v) = call(&app, Method::POST, "/api/ask/answer", "{\"rule\": ").await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    assert!(
        v["error"].as_str().unwrap().starts_with("request body"),
        "{v}"
    );
    let (s, v) = call(&app, Method::POST, "/api/ask/answer", Body::empty()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    assert_eq!(v["path"], "rule");
    for (body, field) in [
        (json!({"samples": 0}), "samples"),
        (json!({"samples": "many"}), "samples"),
        (json!({"seed": -1}), "seed"),
        (json!({"questions": 3}), "questions"),
    ] {
        let (s, v) = call(&app, Method::POST, "/api/ask/next", body.to_string()).await;
        assert_eq!(s, StatusCode::BAD_REQUEST, "{body}: {v}");
        assert!(v["error"].as_str().unwrap().contains(field), "{body}: {v}");
    }
    let big = format!("{{\"pad\": \"{}\"}}", "x".repeat(2 << 20));
    let (s, _) = call(&app, Method::POST, "/api/ask/answer", big.clone()).await;
    assert_eq!(s, StatusCode::PAYLOAD_TOO_LARGE);
    let (s, _) = call(&app, Method::POST, "/api/ask/next", big).await;
    assert_eq!(s, StatusCode::PAYLOAD_TOO_LARGE);
    // Nothing was answered.
    assert!(!dir.join("answers.json").exists());
    // The question is still open after the refusals.
    answer(&app, &q["rule"], false).await;

    // A corrupt answers.json is reported and kept.
    std::fs::write(dir.join("answers.json"), "{\"answers\": [{\"rule\": 1}]}").unwrap();
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/demos",
        demo(&[("R", 200, 200)]).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::CREATED, "{v}");
    let (s, v) = call(&app, Method::POST, "/api/ask/next", Body::empty()).await;
    assert_eq!(s, StatusCode::CONFLICT, "{v}");
    assert!(
        v["error"]
            .as_str()
            .unwrap()
            .starts_with("answers.json: at `answers[0].rule`"),
        "{v}"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("answers.json")).unwrap(),
        "{\"answers\": [{\"rule\": 1}]}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ask_resumes_from_answers_json() {
    let dir = task_dir("ask-resume", true);
    let n0 = demos_on_disk(&dir);
    {
        let app = rccpack::studio::router(&dir).unwrap();
        let q = next_question(&app).await["question"].clone();
        answer(&app, &q["rule"], true).await;
        let q = next_question(&app).await["question"].clone();
        answer(&app, &q["rule"], false).await;
    }
    let learned = std::fs::read_to_string(dir.join("learned.rcc")).unwrap();
    // A fresh router (the studio restarted) continues where it stopped.
    let app = rccpack::studio::router(&dir).unwrap();
    let v = next_question(&app).await;
    assert_eq!(v["progress"]["asked"], 2, "{v}");
    assert_eq!(v["progress"]["dropped"], 1);
    assert_eq!(v["progress"]["confirmed"], 1);
    assert_eq!(v["question"]["number"], 3);
    assert_eq!(demos_on_disk(&dir), n0 + 1);
    assert_eq!(
        std::fs::read_to_string(dir.join("learned.rcc")).unwrap(),
        learned
    );
    assert!(!dir.join("learned.rcc.bak").exists());
    if v["question"].is_object() {
        answer(&app, &v["question"]["rule"], false).await;
        assert_eq!(answers_on_disk(&dir).len(), 3);
    }

    // Saving a demonstration drops the session: the open question is gone
    // and the next one is asked from the files again.
    let q = next_question(&app).await["question"].clone();
    if q.is_object() {
        let (s, _) = call(
            &app,
            Method::POST,
            "/api/demos",
            demo(&[("R", 200, 200), ("G", 380, 200), ("B", 200, 380)]).to_string(),
        )
        .await;
        assert_eq!(s, StatusCode::CREATED);
        let (s, v) = call(
            &app,
            Method::POST,
            "/api/ask/answer",
            json!({"rule": q["rule"], "accepted": false}).to_string(),
        )
        .await;
        assert_eq!(s, StatusCode::CONFLICT, "{v}");
        assert_eq!(v["kind"], "no_question");
        let v = next_question(&app).await;
        assert_eq!(v["progress"]["asked"], answers_on_disk(&dir).len());
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ask_keeps_a_different_learned_rcc_as_backup() {
    let dir = task_dir("ask-backup", true);
    std::fs::write(dir.join("learned.rcc"), "rule mine: DR_N(B, R)\n").unwrap();
    let app = rccpack::studio::router(&dir).unwrap();
    let v = next_question(&app).await;
    assert_eq!(v["backup"], "learned.rcc.bak");
    assert_eq!(
        std::fs::read_to_string(dir.join("learned.rcc.bak")).unwrap(),
        "rule mine: DR_N(B, R)\n"
    );
    assert_ne!(
        std::fs::read_to_string(dir.join("learned.rcc")).unwrap(),
        "rule mine: DR_N(B, R)\n"
    );
}

/// A request with the given headers (`None` content type: none sent).
async fn call_with(
    app: &axum::Router,
    method: Method,
    uri: &str,
    headers: &[(&str, &str)],
    body: impl Into<Body>,
) -> (StatusCode, Value) {
    let mut req = Request::builder().method(method).uri(uri);
    for (k, v) in headers {
        req = req.header(*k, *v);
    }
    let res = app
        .clone()
        .oneshot(req.body(body.into()).unwrap())
        .await
        .unwrap();
    let status = res.status();
    let bytes = res.into_body().collect().await.unwrap().to_bytes();
    let v = serde_json::from_slice(&bytes)
        .unwrap_or(Value::String(String::from_utf8_lossy(&bytes).into()));
    (status, v)
}

/// A page elsewhere cannot change a file or start work
/// (docs/studio.md#security-model, trust of the studio).
#[tokio::test]
async fn foreign_origins_and_simple_requests_are_refused() {
    let dir = task_dir("origin", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let before = std::fs::read(dir.join("demos.json")).unwrap();
    let scene = demo(&[("R", 20, 20)]).to_string();
    let host = ("host", "127.0.0.1:7777");
    let json_ct = ("content-type", "application/json");
    let refused: Vec<Vec<(&str, &str)>> = vec![
        // A "simple" cross-site request: no preflight in a browser.
        vec![
            host,
            ("content-type", "text/plain"),
            ("origin", "http://evil.example"),
        ],
        vec![host, json_ct, ("origin", "http://evil.example")],
        vec![host, json_ct, ("origin", "null")],
        vec![host, json_ct, ("origin", "http://127.0.0.1:8888")],
        vec![host, json_ct, ("sec-fetch-site", "cross-site")],
        vec![host, json_ct, ("sec-fetch-site", "same-site")],
        // A form post, and no content type at all, even without an Origin.
        vec![host, ("content-type", "application/x-www-form-urlencoded")],
        vec![host, ("content-type", "multipart/form-data; boundary=x")],
        vec![host, ("content-type", "text/plain")],
        vec![host],
    ];
    for headers in &refused {
        for (method, uri) in [
            (Method::POST, "/api/demos"),
            (Method::POST, "/api/learn"),
            (Method::POST, "/api/synth"),
            (Method::POST, "/api/ask/next"),
            (Method::POST, "/api/ask/answer"),
            (Method::PUT, "/api/learned"),
            (Method::DELETE, "/api/demos/0"),
            (Method::POST, "/api/synth/1/cancel"),
        ] {
            let (s, v) = call_with(&app, method.clone(), uri, headers, scene.clone()).await;
            assert_eq!(s, StatusCode::FORBIDDEN, "{method} {uri} {headers:?}: {v}");
            assert_eq!(v["kind"], "foreign_request", "{v}");
            assert!(v["error"].as_str().unwrap().contains("refused"), "{v}");
        }
    }
    assert_eq!(std::fs::read(dir.join("demos.json")).unwrap(), before);
    assert!(!dir.join("learned.rcc").exists());
    // The page itself (same origin, JSON) and tools without an Origin pass.
    let (s, v) = call_with(
        &app,
        Method::POST,
        "/api/demos",
        &[
            host,
            json_ct,
            ("origin", "http://127.0.0.1:7777"),
            ("sec-fetch-site", "same-origin"),
        ],
        scene.clone(),
    )
    .await;
    assert_eq!(s, StatusCode::CREATED, "{v}");
    let (s, v) = call_with(
        &app,
        Method::POST,
        "/api/demos",
        &[host, ("content-type", "application/json; charset=utf-8")],
        scene,
    )
    .await;
    assert_eq!(s, StatusCode::CREATED, "{v}");
    // Reading stays open to a GET without any of these headers.
    let (s, _) = call_with(&app, Method::GET, "/api/demos", &[host], Body::empty()).await;
    assert_eq!(s, StatusCode::OK);
}

/// With a question open, a demonstration added to
/// demos.json and a rule added to learned.rcc by hand are never lost when
/// the question is answered.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn answering_never_overwrites_hand_edits() {
    let dir = task_dir("hand-edits", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let q = next_question(&app).await["question"].clone();
    // Hand edits while the question is open.
    let mut demos: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("demos.json")).unwrap()).unwrap();
    demos.as_array_mut().unwrap().push(demo(&[("R", 20, 20)]));
    let demos_text = serde_json::to_string_pretty(&demos).unwrap();
    std::fs::write(dir.join("demos.json"), &demos_text).unwrap();
    let mut rcc = std::fs::read_to_string(dir.join("learned.rcc")).unwrap();
    rcc.push_str("\nrule by_hand: DR_N(B, R)\n");
    std::fs::write(dir.join("learned.rcc"), &rcc).unwrap();
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/ask/answer",
        json!({"rule": q["rule"], "accepted": true}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::CONFLICT, "{v}");
    assert_eq!(v["kind"], "stale_files", "{v}");
    assert_eq!(
        std::fs::read_to_string(dir.join("demos.json")).unwrap(),
        demos_text
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("learned.rcc")).unwrap(),
        rcc
    );
    assert!(!dir.join("answers.json").exists());
    // The next question starts from the files as they are now.
    let v = next_question(&app).await;
    assert!(v["question"].is_object() || v["question"].is_null(), "{v}");
}

/// An outside edit to answers.json (a hand fix, a
/// `rccpack ask` run between two questions) is never overwritten by an
/// answer given in the studio.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn answering_never_overwrites_an_edited_answers_file() {
    let dir = task_dir("hand-answers", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let q = next_question(&app).await["question"].clone();
    let text = "{\n  \"answers\": []\n}\n";
    std::fs::write(dir.join("answers.json"), text).unwrap();
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/ask/answer",
        json!({"rule": q["rule"], "accepted": false}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::CONFLICT, "{v}");
    assert_eq!(v["kind"], "stale_files", "{v}");
    assert!(
        v["error"].as_str().unwrap_or("").contains("answers.json"),
        "{v}"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("answers.json")).unwrap(),
        text
    );
}

/// The studio side of the lock: while `rccpack ask` holds the task
/// folder's lock, the studio writes nothing and says why.
#[tokio::test]
async fn studio_writes_wait_for_the_folder_lock() {
    let dir = task_dir("lock", false);
    let app = rccpack::studio::router(&dir).unwrap();
    let held = rccpack::fsutil::DirLock::try_lock(&dir).unwrap().unwrap();
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/demos",
        demo(&[("R", 20, 20)]).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::CONFLICT, "{v}");
    assert_eq!(v["kind"], "folder_locked");
    assert!(v["error"].as_str().unwrap().contains("rccpack ask"), "{v}");
    assert_eq!(demos_on_disk(&dir), 0);
    drop(held);
    let (s, _) = call(
        &app,
        Method::POST,
        "/api/demos",
        demo(&[("R", 20, 20)]).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::CREATED);
}

/// Many errors in one rule text are reported in linear
/// time (timed as a ratio against a text ten times smaller), at most 20 of
/// them and the count of the rest.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn many_rule_errors_are_reported_in_linear_time() {
    let dir = task_dir("errors", false);
    let app = rccpack::studio::router(&dir).unwrap();
    let texts = |n: usize| -> Vec<String> {
        vec![
            "rule same: DR_N(B, R)\n".repeat(n),
            (0..n).map(|i| format!("rule r{i}: XX_N(B, R)\n")).collect(),
            (0..n)
                .map(|i| format!("rule r{i}: DR_N(B, @nowhere)\n"))
                .collect(),
        ]
    };
    let time = |text: String| {
        let app = app.clone();
        async move {
            let start = std::time::Instant::now();
            let (s, v) = call(
                &app,
                Method::PUT,
                "/api/learned",
                json!({"text": text, "base_version": "absent"}).to_string(),
            )
            .await;
            assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
            (start.elapsed().as_secs_f64(), v)
        }
    };
    for (small, big) in texts(800).into_iter().zip(texts(8000)) {
        // Warm up, then the best of two runs each.
        let _ = time(small.clone()).await;
        let (a1, _) = time(small.clone()).await;
        let (a2, _) = time(small).await;
        let (b1, v) = time(big.clone()).await;
        let (b2, _) = time(big).await;
        let (a, b) = (a1.min(a2), b1.min(b2));
        eprintln!("TIMING small {a:.4} big {b:.4}");
        let e = v["error"].as_str().unwrap();
        assert!(e.lines().count() < 200, "{} lines", e.lines().count());
        assert!(e.contains("more error"), "{e}");
        // Ten times the input: at most ~10× the time (quadratic would be
        // 100×); generous for a loaded machine.
        assert!(b < 30.0 * a.max(0.002), "small {a:.4} s, big {b:.4} s");
    }
}

/// Learned rules about a class the problem
/// lacks are noted, not refused; `cutoff` is named as the body's field.
#[tokio::test]
async fn absent_classes_are_noted_and_fields_named() {
    let dir = task_dir("absent", false);
    let app = rccpack::studio::router(&dir).unwrap();
    let (s, v) = call(
        &app,
        Method::PUT,
        "/api/learned",
        json!({"text": "rule y: DR_N(Y, R)\n", "base_version": "absent"}).to_string(),
    )
    .await;
    // Y is in no demonstration either: a typo, refused.
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    // A demonstration with a class the problem lacks: rules about it are
    // noted, not refused.
    let mut d = demo(&[("R", 20, 20)]);
    d["objects"]
        .as_array_mut()
        .unwrap()
        .push(json!({"id": "y0", "class": "Y", "x": 60, "y": 60, "width": 20, "height": 20}));
    std::fs::write(dir.join("demos.json"), json!([d]).to_string()).unwrap();
    let (s, v) = call(
        &app,
        Method::PUT,
        "/api/learned",
        json!({"text": "rule y: DR_N(Y, R)\n", "base_version": "absent"}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert!(
        v["note"]
            .as_str()
            .unwrap()
            .contains("no objects of class Y"),
        "{v}"
    );
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/learn",
        json!({"cutoff": 2.0}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    let e = v["error"].as_str().unwrap();
    assert!(e.contains("cutoff") && !e.contains("--cutoff"), "{e}");
    assert_eq!(v["path"], "cutoff");
}

/// "Another layout like this": `POST /api/sample` draws a layout
/// of at least the given score; each seed another one; every one verified.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn another_layout_like_this() {
    let dir = task_dir("sample", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let pilot = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/box-packing/pilot.rcc"),
    )
    .unwrap();
    let problem = rccpack::scene::Scene::from_json(
        &std::fs::read_to_string(dir.join("problem.json")).unwrap(),
    )
    .unwrap();
    let rules = rccpack::rules::parse_rules(&pilot).unwrap();
    let mut layouts = Vec::new();
    for seed in 1..=3 {
        let (s, v) = call(
            &app,
            Method::POST,
            "/api/sample",
            json!({"rules": pilot, "min_score": 1.0, "seed": seed}).to_string(),
        )
        .await;
        assert_eq!(s, StatusCode::OK, "{v}");
        assert_eq!(v["sampled"], true);
        let scene = rccpack::scene::Scene::from_json(&v["scene"].to_string()).unwrap();
        rccpack::synth::verify_solution(&problem, &scene, &rules, rccpack::Contact::Point).unwrap();
        let ev = rccpack::evaluate(&scene, &rules, rccpack::Contact::Point);
        assert_eq!((ev.score, v["score"].as_f64()), (1.0, Some(1.0)));
        layouts.push(scene);
    }
    assert!(
        layouts.windows(2).any(|w| w[0] != w[1]),
        "three draws, one layout"
    );
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/sample",
        json!({"rules": pilot, "min_score": 1.5}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    assert!(v["error"].as_str().unwrap().contains("min_score"), "{v}");
}

/// A learning request whose client leaves is cancelled
/// (no core kept busy), and a newer request cancels an older one.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn left_learning_requests_are_cancelled() {
    let dir = task_dir("learn-cancel", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let jobs = |app: axum::Router| async move {
        let (_, t) = call(&app, Method::GET, "/api/task", Body::empty()).await;
        t["learning_jobs"].as_u64().expect("learning_jobs")
    };
    let slow = json!({"samples": 1_000_000}).to_string();
    let left = tokio::time::timeout(
        std::time::Duration::from_millis(300),
        call(&app, Method::POST, "/api/learn", slow.clone()),
    )
    .await;
    assert!(left.is_err(), "10^6 samples learned in 0.3 s?");
    let start = std::time::Instant::now();
    while jobs(app.clone()).await > 0 {
        assert!(
            start.elapsed() < std::time::Duration::from_secs(5),
            "learning still runs after its client left"
        );
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
    // One job per folder: the second request cancels the first.
    let first = tokio::spawn({
        let app = app.clone();
        async move { call(&app, Method::POST, "/api/learn", slow).await }
    });
    tokio::time::sleep(std::time::Duration::from_millis(300)).await;
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/learn",
        json!({"samples": 200}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let (s, v) = tokio::time::timeout(std::time::Duration::from_secs(5), first)
        .await
        .expect("the older request ends")
        .unwrap();
    assert_eq!(s, StatusCode::CONFLICT, "{v}");
    assert_eq!(v["kind"], "cancelled", "{v}");
}

/// Smaller cases: a 405 is JSON; a demos.json that is not
/// UTF-8 is 409 (corrupt, with the byte offset), not 500; a problem.json
/// that is not UTF-8 names the byte offset.
#[tokio::test]
async fn method_not_allowed_and_non_utf8_files() {
    let dir = task_dir("405-utf8", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let (s, v) = call(&app, Method::PUT, "/api/task", Body::empty()).await;
    assert_eq!(s, StatusCode::METHOD_NOT_ALLOWED, "{v}");
    assert_eq!(v["kind"], "method_not_allowed", "{v}");
    assert!(v["error"].as_str().unwrap().contains("method"), "{v}");
    std::fs::write(dir.join("demos.json"), b"[\n\xff]").unwrap();
    let (s, v) = call(&app, Method::GET, "/api/demos", Body::empty()).await;
    assert_eq!(s, StatusCode::CONFLICT, "{v}");
    assert_eq!(v["kind"], "corrupt_demos", "{v}");
    assert!(
        v["error"].as_str().unwrap().contains("byte offset 2"),
        "{v}"
    );
    std::fs::write(dir.join("problem.json"), b"{\n\xff}").unwrap();
    let e = rccpack::studio::router(&dir).unwrap_err().to_string();
    assert!(
        e.contains("byte offset 2") && !e.contains("needs a problem.json"),
        "{e}"
    );
}

/// `POST /api/learn` with 200 samples, answered 200.
async fn learn_200(app: &axum::Router) -> Value {
    let body = json!({"samples": 200}).to_string();
    let (s, v) = call(app, Method::POST, "/api/learn", body).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    v
}

/// Priors from a small library: the two bundled examples, each with its
/// intended rules as learned.rcc.
fn library_priors(tag: &str) -> rccpack::priors::Priors {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let lib = crate::support::scratch(&format!("studio-lib-{tag}"));
    let mut dirs = Vec::new();
    for (name, learned) in [("box-packing", "pilot.rcc"), ("shelf", "intended.rcc")] {
        let d = lib.join(name);
        std::fs::create_dir_all(&d).unwrap();
        std::fs::copy(examples.join(name).join("demos.json"), d.join("demos.json")).unwrap();
        std::fs::copy(examples.join(name).join(learned), d.join("learned.rcc")).unwrap();
        dirs.push(d);
    }
    rccpack::task::library::library(&dirs, &rccpack::priors::PriorParams::default()).unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn studio_learns_and_asks_with_priors() {
    let priors = std::sync::Arc::new(library_priors("learn"));
    let dir = task_dir("priors", true);
    let opts = rccpack::studio::StudioOptions {
        priors: Some(priors.clone()),
    };
    let app = rccpack::studio::router_with(&dir, opts).unwrap();
    let (_, t) = call(&app, Method::GET, "/api/task", Body::empty()).await;
    assert_eq!(t["priors"]["tasks"], 2, "{t}");
    assert_eq!(t["priors"]["hash"], priors.hash_text().as_str());

    // POST /api/learn learns what `learn_with` with priors learns.
    let v = learn_200(&app).await;
    let demos =
        scenes_from_json(&std::fs::read_to_string(dir.join("demos.json")).unwrap()).unwrap();
    let params = rccpack::infer::LearnParams {
        samples: 200,
        ..Default::default()
    };
    let expected = rccpack::infer::learn_with(
        &demos,
        None,
        &params,
        &rccpack::infer::LearnOptions {
            priors: Some(&priors),
            ..Default::default()
        },
    )
    .unwrap();
    let rcc = expected.to_rcc();
    let header = rcc.split("\n\n").next().unwrap().to_string() + "\n";
    assert!(header.contains("\n# priors fnv1a64:"), "{header}");
    assert_eq!(v["header"], header.as_str());
    let names: Vec<&str> = v["rules"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["name"].as_str().unwrap())
        .collect();
    let expected_rules = expected.rules();
    let expected_names: Vec<&str> = expected_rules
        .rules
        .iter()
        .map(|r| r.name.as_str())
        .collect();
    assert_eq!(names, expected_names);
    assert_eq!(v["statements"], expected.statements.len());

    // The questions learn with them too: learned.rcc at the session's start.
    let q = next_question(&app).await;
    let text = q["learned"]["text"].as_str().unwrap();
    assert!(text.contains("\n# priors fnv1a64:"), "{text}");

    // Without priors: none in the task, none in the header.
    let plain_dir = task_dir("no-priors", true);
    let plain = rccpack::studio::router(&plain_dir).unwrap();
    let (_, t) = call(&plain, Method::GET, "/api/task", Body::empty()).await;
    assert_eq!(t["priors"], Value::Null);
    let v = learn_200(&plain).await;
    assert!(!v["header"].as_str().unwrap().contains("# priors"), "{v}");
}

#[test]
fn studio_refuses_a_bad_priors_file_naming_the_field() {
    let dir = task_dir("bad-priors", true);
    let text = library_priors("bad").to_json();
    let bad = dir.join("priors.json");
    std::fs::write(&bad, text.replacen("\"tasks\": 2", "\"tasks\": 3", 1)).unwrap();
    let mut child = crate::support::command()
        .arg("studio")
        .arg(&dir)
        .arg("--priors")
        .arg(&bad)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // A studio that took the file would serve until stopped: stop it.
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > std::time::Duration::from_secs(60) {
            let _ = child.kill();
            panic!("rccpack studio started with a damaged priors file");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("priors.json"), "{stderr}");
    assert!(stderr.contains("field `hash`"), "{stderr}");
}

/// "Check rules" with a slip rate asks first whether the demonstration
/// that looks like a slip is meant; "not like that" makes it a slip for sure (journaled
/// as `rccpack ask` journals it), demos.json untouched.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ask_asks_about_a_suspect_first() {
    let (problem, slipped, sl) = crate::measured::slipped_task0();
    let dir = crate::support::scratch("studio-ask-suspect");
    std::fs::write(dir.join("problem.json"), problem.to_json()).unwrap();
    let demos = rccpack::scene::scenes_to_json(&slipped);
    std::fs::write(dir.join("demos.json"), &demos).unwrap();
    let app = rccpack::studio::router(&dir).unwrap();
    // Learn names the suspect; without a slip rate there is no `suspects`.
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/learn",
        json!({"slip_rate": 0.01}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["suspects"][0]["demonstration"], sl.demonstration, "{v}");
    assert_eq!(v["suspects"][0]["object"], sl.object.as_str(), "{v}");
    let (_, v) = call(&app, Method::POST, "/api/learn", "{}").await;
    assert!(v.get("suspects").is_none(), "{v}");
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/ask/next",
        json!({"samples": 1000, "slip_rate": 0.01}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let q = &v["question"];
    assert_eq!(q["suspect"]["demonstration"], sl.demonstration, "{q}");
    assert_eq!(q["suspect"]["objects"][0], sl.object.as_str(), "{q}");
    let shown: Value = serde_json::from_str(&slipped[sl.demonstration].to_json()).unwrap();
    assert_eq!(q["scene"], shown);
    let a = answer(&app, &q["rule"], false).await;
    assert_eq!(a["answer"]["suspect"], sl.demonstration, "{a}");
    let answers = answers_on_disk(&dir);
    assert_eq!(answers[0]["suspect"]["demonstration"], sl.demonstration);
    assert_eq!(
        std::fs::read_to_string(dir.join("demos.json")).unwrap(),
        demos
    );
    let rcc = std::fs::read_to_string(dir.join("learned.rcc")).unwrap();
    assert!(
        rcc.contains("answered as a slip; it no longer counts"),
        "{rcc}"
    );
    // A question without a suspect has no `suspect` field.
    let v = next_question(&app).await;
    if let Some(q) = v["question"].as_object() {
        assert!(!q.contains_key("suspect") || q["suspect"]["demonstration"] != sl.demonstration);
    }
}

/// A measured demos.json (a camera's fractions): the studio lists it on
/// the grid, and saving or deleting a demonstration keeps every other
/// recorded entry as it was.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn measured_demonstrations_are_listed_on_the_grid_and_kept_as_recorded() {
    let dir = task_dir("measured", false);
    let a = demo(&[("R", 200, 200), ("R", 220, 200), ("B", 200, 220)]);
    let mut m = a.clone();
    m["objects"][4]["x"] = json!(201.7);
    m["objects"][5]["y"] = json!(198.6);
    let recorded = json!([m.clone(), a.clone()]);
    std::fs::write(dir.join("demos.json"), recorded.to_string()).unwrap();
    let app = rccpack::studio::router(&dir).unwrap();
    let (s, v) = call(&app, Method::GET, "/api/demos", Body::empty()).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["count"], 2);
    assert_eq!(v["demos"][0], v["demos"][1], "snapped to the grid: {v}");
    let on_disk = || -> Vec<Value> {
        serde_json::from_str(&std::fs::read_to_string(dir.join("demos.json")).unwrap()).unwrap()
    };
    let b = demo(&[("R", 240, 200), ("R", 260, 200), ("B", 240, 220)]);
    let (s, v) = call(&app, Method::POST, "/api/demos", b.to_string()).await;
    assert_eq!(s, StatusCode::CREATED, "{v}");
    let after = on_disk();
    assert_eq!(after.len(), 3);
    assert_eq!(after[0], m, "the measured entry is kept as recorded");
    let (_, list) = call(&app, Method::GET, "/api/demos", Body::empty()).await;
    let version = list["version"].as_str().unwrap().to_string();
    let (s, v) = call(
        &app,
        Method::DELETE,
        &format!("/api/demos/1?version={version}"),
        Body::empty(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let after = on_disk();
    assert_eq!(after.len(), 2);
    assert_eq!(after[0], m, "still as recorded");
}

/// Hardening, third pass, item 2: the page's own delete never breaks
/// "Check rules" — a demonstration the journal refers to (or one before
/// it) is not deleted, with a reason; one after them is.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn delete_refuses_a_demonstration_the_answers_refer_to() {
    let dir = task_dir("delete-answered", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let n0 = demos_on_disk(&dir);
    let q = next_question(&app).await["question"].clone();
    let v = answer(&app, &q["rule"], true).await;
    assert_eq!(v["answer"]["demo"], n0, "the probe is demonstration {n0}");
    let version = || async {
        let (_, l) = call(&app, Method::GET, "/api/demos", Body::empty()).await;
        l["version"].as_str().unwrap().to_string()
    };
    for i in [0, n0] {
        let (s, v) = call(
            &app,
            Method::DELETE,
            &format!("/api/demos/{i}?version={}", version().await),
            Body::empty(),
        )
        .await;
        assert_eq!(s, StatusCode::CONFLICT, "{v}");
        assert_eq!(v["kind"], "answered_demo", "{v}");
        assert!(
            v["error"]
                .as_str()
                .unwrap()
                .contains("answers.json refers to demonstration"),
            "{v}"
        );
    }
    assert_eq!(demos_on_disk(&dir), n0 + 1, "nothing deleted");
    // Check rules goes on.
    let (s, v) = call(
        &app,
        Method::POST,
        "/api/ask/next",
        json!({"samples": 200}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    // A demonstration saved after the answers can go.
    let extra = demo(&[("R", 200, 200), ("R", 220, 200), ("B", 200, 220)]);
    let (s, _) = call(&app, Method::POST, "/api/demos", extra.to_string()).await;
    assert_eq!(s, StatusCode::CREATED);
    let (s, v) = call(
        &app,
        Method::DELETE,
        &format!("/api/demos/{}?version={}", n0 + 1, version().await),
        Body::empty(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
}

/// Hardening, third pass, item 9: the learning a "Check rules" request
/// starts ends when its client leaves, as POST /api/learn's does — the
/// folder is free again at once, not after a million random layouts.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ask_learning_stops_when_its_client_leaves() {
    let dir = task_dir("ask-leave", true);
    let app = rccpack::studio::router(&dir).unwrap();
    let slow = call(
        &app,
        Method::POST,
        "/api/ask/next",
        json!({"samples": 1_000_000}).to_string(),
    );
    // The client gives up.
    assert!(
        tokio::time::timeout(std::time::Duration::from_millis(500), slow)
            .await
            .is_err(),
        "a million samples take longer than half a second"
    );
    let start = std::time::Instant::now();
    loop {
        let (s, v) = call(
            &app,
            Method::POST,
            "/api/ask/next",
            json!({"samples": 200}).to_string(),
        )
        .await;
        if s == StatusCode::OK {
            break;
        }
        assert_eq!(s, StatusCode::CONFLICT, "{v}");
        assert!(
            // Measured: about 0.2 s after the client left; a million
            // samples take about 5 s in a debug build.
            start.elapsed() < std::time::Duration::from_secs(3),
            "the left request's learning still holds the folder: {v}"
        );
        tokio::time::sleep(std::time::Duration::from_millis(100)).await;
    }
}

#[tokio::test]
async fn a_turned_block_is_saved_turned_and_a_bad_turn_is_refused_by_field() {
    let dir = task_dir("turned", false);
    let app = rccpack::studio::router(&dir).unwrap();
    let mut d = demo(&[("R", 200, 200), ("G", 220, 200)]);
    let last = d["objects"].as_array().unwrap().len() - 1;
    d["objects"][last]["turned"] = json!(true);
    let (s, v) = call(&app, Method::POST, "/api/demos", d.to_string()).await;
    assert_eq!(s, StatusCode::CREATED, "{v}");
    let saved =
        scenes_from_json(&std::fs::read_to_string(dir.join("demos.json")).unwrap()).unwrap();
    assert!(saved[0].objects.iter().any(|o| o.turned && o.id == "g1"));
    d["objects"][last]["turned"] = json!("yes");
    let (s, v) = call(&app, Method::POST, "/api/demos", d.to_string()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert_eq!(v["path"], format!("objects[{last}].turned"), "{v}");
    // The board draws footprints and the recorder turns blocks.
    let (_, board) = call(&app, Method::GET, "/assets/board.js", Body::empty()).await;
    assert!(board
        .as_str()
        .unwrap()
        .contains("export function footprint(o)"));
    let (_, app_js) = call(&app, Method::GET, "/assets/app.js", Body::empty()).await;
    assert!(app_js.as_str().unwrap().contains("function turnSelected()"));
}
