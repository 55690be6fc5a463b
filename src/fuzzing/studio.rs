//! The studio harness: requests through the studio's router on a fresh
//! temporary task folder.

use arbitrary::{Result as AResult, Unstructured};

const STUDIO_PROBLEM: &str = r#"{"space":{"width":40,"height":40},"grid":10,"objects":[
  {"id":"w","class":"W","x":0,"y":0,"width":40,"height":10,"fixed":true},
  {"id":"r1","class":"R","width":10,"height":10},
  {"id":"b1","class":"B","width":10,"height":10}]}"#;

const STUDIO_DEMO: &str = r#"{"space":{"width":40,"height":40},"grid":10,"objects":[
  {"id":"w","class":"W","x":0,"y":0,"width":40,"height":10,"fixed":true},
  {"id":"r1","class":"R","x":0,"y":10,"width":10,"height":10},
  {"id":"b1","class":"B","x":0,"y":20,"width":10,"height":10}]}"#;

fn runtime() -> &'static tokio::runtime::Runtime {
    static RT: std::sync::OnceLock<tokio::runtime::Runtime> = std::sync::OnceLock::new();
    RT.get_or_init(|| {
        tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .unwrap_or_else(|e| panic!("cannot start a runtime for the harness: {e}"))
    })
}

struct Request {
    method: axum::http::Method,
    uri: String,
    host: Option<String>,
    body: Vec<u8>,
}

fn request(u: &mut Unstructured) -> AResult<Request> {
    use axum::http::Method;
    let method = u
        .choose(&[
            Method::GET,
            Method::POST,
            Method::PUT,
            Method::DELETE,
            Method::PATCH,
        ])?
        .clone();
    let tail: String = u.arbitrary()?;
    let uri = match u.int_in_range(0..=13)? {
        0 => "/".to_string(),
        1 => "/api/task".into(),
        2 => "/api/demos".into(),
        3 => format!("/api/demos/{}", u.int_in_range(0u8..=3)?),
        4 => format!("/api/demos/{tail}"),
        5 => "/api/learn".into(),
        6 => "/api/learned".into(),
        7 => "/api/synth".into(),
        8 => format!("/api/synth/{}", u.int_in_range(0u8..=3)?),
        9 => format!("/api/synth/{}/cancel", u.int_in_range(0u8..=3)?),
        10 => format!("/assets/{tail}"),
        11 => format!("/api/demos/0?version={tail}"),
        12 => format!("/{tail}"),
        _ => tail,
    };
    let host = if u.ratio(1, 8)? {
        Some(u.arbitrary()?)
    } else {
        None
    };
    let body = match u.int_in_range(0..=5)? {
        0 => Vec::new(),
        1 => STUDIO_DEMO.as_bytes().to_vec(),
        2 => format!(
            r#"{{"rules":"rule a: EC_S(B, R)\n","time_limit":{},"seed":{}}}"#,
            u.int_in_range(0u8..=3)?,
            u.int_in_range(0u8..=3)?
        )
        .into_bytes(),
        3 => {
            let text: String = u.arbitrary()?;
            serde_json::json!({"text": text, "base_version": "absent"})
                .to_string()
                .into_bytes()
        }
        _ => u.arbitrary::<Vec<u8>>()?,
    };
    Ok(Request {
        method,
        uri,
        host,
        body,
    })
}

/// Keep the harness fast: a learn body asking for many samples, or a synth
/// body with a long time limit, is scaled down (the limits themselves are
/// tested elsewhere; here only the handling of the request matters).
fn tame(req: &mut Request) {
    if let Ok(mut v) = serde_json::from_slice::<serde_json::Value>(&req.body) {
        let mut changed = false;
        if let Some(n) = v.get("samples").and_then(serde_json::Value::as_u64) {
            if (21..=crate::limits::MAX_SAMPLES as u64).contains(&n) {
                v["samples"] = serde_json::json!(20);
                changed = true;
            }
        }
        if let Some(t) = v.get("time_limit").and_then(serde_json::Value::as_f64) {
            if t > 2.0 && t <= 600.0 {
                v["time_limit"] = serde_json::json!(2);
                changed = true;
            }
        }
        if changed {
            req.body = v.to_string().into_bytes();
        }
    }
}

fn list_dir(dir: &std::path::Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

fn studio_inner(u: &mut Unstructured, root: &std::path::Path) -> AResult<()> {
    use tower::ServiceExt;
    let task = root.join("task");
    std::fs::create_dir_all(&task).unwrap_or_else(|e| panic!("cannot create {task:?}: {e}"));
    let write = |name: &str, text: &str| {
        std::fs::write(task.join(name), text).unwrap_or_else(|e| panic!("cannot write: {e}"))
    };
    write("problem.json", STUDIO_PROBLEM);
    if u.arbitrary()? {
        write("demos.json", &format!("[{STUDIO_DEMO}]"));
    }
    if u.ratio(1, 4)? {
        let text: String = u.arbitrary()?;
        write("statements.rcc", &text);
    }
    let app = match crate::studio::router(&task) {
        Ok(a) => a,
        Err(e) => panic!("the studio refuses a valid task folder: {e}"),
    };
    let n = u.int_in_range(1..=4)?;
    for _ in 0..n {
        let mut req = request(u)?;
        tame(&mut req);
        let mut b = axum::http::Request::builder()
            .method(req.method.clone())
            .uri(req.uri.as_str());
        if let Some(h) = &req.host {
            b = b.header(axum::http::header::HOST, h.as_str());
        }
        // The page's own requests are JSON (any other content type is
        // refused before a handler runs, which would hide the handlers).
        b = b.header(axum::http::header::CONTENT_TYPE, "application/json");
        // A URI or header the HTTP types refuse never reaches the server.
        let Ok(http_req) = b.body(axum::body::Body::from(req.body.clone())) else {
            continue;
        };
        let res = runtime().block_on(async {
            let res = app.clone().oneshot(http_req).await;
            match res {
                Ok(r) => {
                    let status = r.status();
                    let body = axum::body::to_bytes(r.into_body(), 16 << 20).await;
                    (status, body.map(|b| b.len()).unwrap_or(0))
                }
                Err(e) => match e {},
            }
        });
        assert!(
            !res.0.is_server_error(),
            "{} {} answered {} (body {:?})",
            req.method,
            req.uri,
            res.0,
            String::from_utf8_lossy(&req.body)
        );
    }
    // Nothing outside the task folder; inside, only the task's file names.
    assert_eq!(list_dir(root), ["task"], "written outside the task folder");
    for name in list_dir(&task) {
        assert!(
            matches!(
                name.as_str(),
                "problem.json" | "demos.json" | "statements.rcc" | "learned.rcc"
            ) || name == crate::fsutil::LOCK_FILE,
            "unexpected file {name} in the task folder"
        );
    }
    Ok(())
}

/// Requests (method, path, body, sometimes a Host header) through the
/// studio's router with `oneshot` on a fresh temporary task folder → a
/// status below 500, never a panic, nothing written outside the folder.
pub fn studio(data: &[u8]) {
    static N: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let root = std::env::temp_dir().join(format!(
        "rccpack-fuzz-studio-{}-{}",
        std::process::id(),
        N.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&root);
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let _ = studio_inner(&mut Unstructured::new(data), &root);
    }));
    let _ = std::fs::remove_dir_all(&root);
    if let Err(p) = result {
        std::panic::resume_unwind(p);
    }
}
