//! The layers every request passes: loopback `Host` only, changes only from
//! the studio's own page, and the JSON form of the router's own 413 and 405
//! answers.

use super::ApiError;
use crate::limits::cut;
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};

/// Refuse requests whose `Host` names anything but this machine's loopback
/// (a page elsewhere reaching the studio through DNS rebinding).
pub(crate) async fn local_host_only(
    req: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    if let Some(h) = req.headers().get(header::HOST) {
        let host = h.to_str().unwrap_or("");
        let name = match host.rsplit_once(':') {
            Some((n, port)) if port.bytes().all(|b| b.is_ascii_digit()) => n,
            _ => host,
        };
        if !matches!(name, "127.0.0.1" | "localhost" | "[::1]") {
            return ApiError::new(
                StatusCode::FORBIDDEN,
                format!(
                    "host `{}` refused: the studio answers only on 127.0.0.1",
                    cut(host)
                ),
            )
            .into_response();
        }
    }
    next.run(req).await
}

/// Refuse every request that changes a file or starts work (any method but
/// `GET`/`HEAD`) unless it comes from the studio's own page (docs/studio.md#security-model
/// "Trust of the studio"): an `Origin` header, when sent, must be this
/// server's own (`http://` + the `Host` header; `null` and every other
/// origin are refused); a `Sec-Fetch-Site` header, when sent, must be
/// `same-origin` (or `none`, typed by the person); and the body must be
/// declared `application/json` — a type a page elsewhere cannot send
/// without a CORS preflight, which the studio never grants. Requests with
/// no `Origin` (curl, scripts on this machine) pass these checks.
pub(crate) async fn same_origin_only(
    req: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    use axum::http::Method;
    if matches!(*req.method(), Method::GET | Method::HEAD) {
        return next.run(req).await;
    }
    let headers = req.headers();
    let text = |name: &str| {
        headers
            .get(name)
            .map(|v| String::from_utf8_lossy(v.as_bytes()).into_owned())
    };
    let refuse = |why: String| {
        ApiError::new(StatusCode::FORBIDDEN, why)
            .kind("foreign_request")
            .into_response()
    };
    if let Some(origin) = text("origin") {
        let host = text("host");
        let own = match &host {
            Some(h) => origin.eq_ignore_ascii_case(&format!("http://{h}")),
            // No Host (HTTP/1.0, tests): a loopback origin only.
            None => origin
                .strip_prefix("http://")
                .map(|o| match o.rsplit_once(':') {
                    Some((n, p)) if p.bytes().all(|b| b.is_ascii_digit()) => n,
                    _ => o,
                })
                .is_some_and(|n| matches!(n, "127.0.0.1" | "localhost" | "[::1]")),
        };
        if !own {
            return refuse(format!(
                "origin `{}` refused: only the studio's own page may change files or start work",
                cut(&origin)
            ));
        }
    }
    if let Some(site) = text("sec-fetch-site") {
        if !matches!(site.as_str(), "same-origin" | "none") {
            return refuse(format!(
                "a {} request refused (Sec-Fetch-Site: {}): only the studio's own page may change files or start work",
                req.method(),
                cut(&site)
            ));
        }
    }
    let json_body = text("content-type").is_some_and(|t| {
        t.split(';')
            .next()
            .is_some_and(|m| m.trim().eq_ignore_ascii_case("application/json"))
    });
    if !json_body {
        return refuse(format!(
            "content type `{}` refused; expected application/json (a {} request changes files or starts work)",
            cut(&text("content-type").unwrap_or_else(|| "(none)".into())),
            req.method()
        ));
    }
    next.run(req).await
}

/// Answer a body past [`crate::studio::BODY_LIMIT`] with the studio's JSON error
/// form (the body-limit layers answer 413 in plain text), and a method a
/// route does not take too (the router answers 405 with an empty body).
pub(crate) async fn json_413(
    req: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    let res = next.run(req).await;
    let is_json = res
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|t| t.as_bytes().starts_with(b"application/json"));
    if res.status() == StatusCode::PAYLOAD_TOO_LARGE && !is_json {
        return ApiError::new(
            StatusCode::PAYLOAD_TOO_LARGE,
            format!(
                "request body is too large; expected at most {} bytes (1 MiB)",
                crate::studio::BODY_LIMIT
            ),
        )
        .kind("too_large")
        .into_response();
    }
    if res.status() == StatusCode::METHOD_NOT_ALLOWED && !is_json {
        // The router's 405 has an empty body; every error is JSON.
        let allow = res.headers().get(header::ALLOW).cloned();
        let mut r = ApiError::new(
            StatusCode::METHOD_NOT_ALLOWED,
            format!(
                "method not allowed here; expected {}",
                allow
                    .as_ref()
                    .and_then(|a| a.to_str().ok())
                    .unwrap_or("another method (see docs/studio-api.md)")
            ),
        )
        .kind("method_not_allowed")
        .into_response();
        if let Some(a) = allow {
            r.headers_mut().insert(header::ALLOW, a);
        }
        return r;
    }
    res
}
