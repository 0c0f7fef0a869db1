//! `gcs serve FILE`: a local page where the model is edited, checked, solved and drawn as its
//! params move.
//!
//! The server (tiny_http, one request at a time) answers only:
//!
//! - `GET /`, `/style.css`, `/app.js`: the page, embedded in the binary (`page/`);
//! - `GET /api/model`: the file's name and its text, read from disk at each request (the
//!   only file the server reads; it writes none);
//! - `POST /api/check`, `/api/solve`, `/api/compile`: the JSON API of [`api`], whose
//!   requests carry the editor's text.
//!
//! Anything else is a 404 (no path is ever mapped to a file), a body over [`MAX_BODY`] a 413,
//! and a request whose `Host` is not the loopback address the server is bound to a 403 (a page
//! elsewhere cannot reach it through a name of its own). A model that does not parse, analyse
//! or solve is an answer like any other, and a panic while answering (a bug in gcs) is a 500:
//! the server goes on.

pub mod api;

use std::io::{Read as _, Write as _};
use std::net::{IpAddr, SocketAddr};
use std::path::Path;
use std::process::ExitCode;
use tiny_http::{Header, Method, Response, Server};

/// The largest request body read, in bytes: a model's text with room to spare.
pub const MAX_BODY: usize = 1 << 20;

/// The page, as files kept beside this module and embedded at build time.
const INDEX_HTML: &str = include_str!("page/index.html");
const STYLE_CSS: &str = include_str!("page/style.css");
const APP_JS: &str = include_str!("page/app.js");

/// Serves the model at `path` on `host:port` (port 0: a free one) until the process is
/// stopped. The first line on standard output is the page's URL.
pub fn run(path: &Path, host: &str, port: u16) -> ExitCode {
    let name = path.display().to_string();
    if let Err(e) = std::fs::read(path) {
        eprintln!("error: cannot read `{name}`: {e}");
        return ExitCode::from(2);
    }
    let ip: IpAddr = match host.parse() {
        Ok(ip) => ip,
        Err(_) if host == "localhost" => IpAddr::from([127, 0, 0, 1]),
        Err(_) => {
            eprintln!("error: `--host {host}`: not an IP address (127.0.0.1, ::1, 0.0.0.0)");
            return ExitCode::from(2);
        }
    };
    let server = match listen(SocketAddr::new(ip, port)) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: cannot listen on {host}:{port}: {e}");
            return ExitCode::from(2);
        }
    };
    let Some(bound) = server.server_addr().to_ip() else {
        eprintln!("error: the server has no IP address");
        return ExitCode::from(2);
    };
    let url = match bound {
        SocketAddr::V4(a) => format!("http://{}:{}/", a.ip(), a.port()),
        SocketAddr::V6(a) => format!("http://[{}]:{}/", a.ip(), a.port()),
    };
    outln!("{url}");
    eprintln!("serving `{name}` at {url} (Ctrl-C stops)");
    let _ = std::io::stdout().flush();
    let mut api = api::Api::new(name.clone());
    for mut request in server.incoming_requests() {
        let reply = answer(&mut api, path, bound, &mut request);
        let mut response = Response::from_data(reply.body).with_status_code(reply.status);
        let allow = (reply.status == 405).then_some(("Allow", "GET, POST"));
        let headers = [
            ("Content-Type", reply.content_type),
            ("Cache-Control", "no-store"),
            ("X-Content-Type-Options", "nosniff"),
        ];
        for (name, value) in headers.into_iter().chain(allow) {
            if let Ok(h) = Header::from_bytes(name.as_bytes(), value.as_bytes()) {
                response.add_header(h);
            }
        }
        // A client that went away is no reason to stop.
        let _ = request.respond(response);
    }
    ExitCode::SUCCESS
}

/// The server, listening on `addr` with Nagle's algorithm off on every connection (Linux
/// passes the listener's `TCP_NODELAY` to the connections it accepts): tiny_http writes a
/// response's head and body apart, and on a kept-alive connection Nagle held the body until the
/// client acknowledged the head, which it delays: 40 ms of every answer (1.6 ms without).
fn listen(addr: SocketAddr) -> Result<Server, Box<dyn std::error::Error + Send + Sync>> {
    use socket2::{Domain, Socket, Type};
    let socket = Socket::new(Domain::for_address(addr), Type::STREAM, None)?;
    socket.set_reuse_address(true)?;
    socket.set_tcp_nodelay(true)?;
    socket.bind(&addr.into())?;
    socket.listen(128)?;
    Server::from_listener(std::net::TcpListener::from(socket), None)
}

/// A response: status, content type and body.
struct Reply {
    status: u16,
    content_type: &'static str,
    body: Vec<u8>,
}

impl Reply {
    fn json(status: u16, body: &serde_json::Value) -> Reply {
        Reply {
            status,
            content_type: "application/json",
            body: body.to_string().into_bytes(),
        }
    }

    fn error(status: u16, why: &str) -> Reply {
        Reply::json(status, &serde_json::json!({ "ok": false, "error": why }))
    }

    fn page(content_type: &'static str, text: &'static str) -> Reply {
        Reply {
            status: 200,
            content_type,
            body: text.as_bytes().to_vec(),
        }
    }
}

/// The reply to one request.
fn answer(
    api: &mut api::Api,
    path: &Path,
    bound: SocketAddr,
    request: &mut tiny_http::Request,
) -> Reply {
    if !host_allowed(bound, request) {
        return Reply::error(403, "this server answers only at its own loopback address");
    }
    let url = request.url();
    let route = url.split(['?', '#']).next().unwrap_or(url).to_string();
    let method = request.method().clone();
    match (&method, route.as_str()) {
        (Method::Get | Method::Head, "/" | "/index.html") => {
            Reply::page("text/html; charset=utf-8", INDEX_HTML)
        }
        (Method::Get | Method::Head, "/style.css") => {
            Reply::page("text/css; charset=utf-8", STYLE_CSS)
        }
        (Method::Get | Method::Head, "/app.js") => {
            Reply::page("text/javascript; charset=utf-8", APP_JS)
        }
        (Method::Get | Method::Head, "/api/model") => match std::fs::read(path) {
            Ok(bytes) => Reply::json(
                200,
                &serde_json::json!({
                    "name": path.display().to_string(),
                    "text": String::from_utf8_lossy(&bytes),
                }),
            ),
            Err(e) => Reply::error(500, &format!("cannot read `{}`: {e}", path.display())),
        },
        (Method::Post, "/api/check" | "/api/solve" | "/api/compile") => {
            let body = match read_body(request) {
                Ok(b) => b,
                Err(reply) => return reply,
            };
            // A panic is a bug in gcs: the request fails, the server goes on, with the model
            // compiled again at the next request.
            let answered = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                api.answer(&route, &body)
            }));
            match answered {
                Ok(a) => Reply::json(a.status, &a.body),
                Err(_) => {
                    *api = api::Api::new(path.display().to_string());
                    Reply::error(
                        500,
                        "internal error: gcs panicked (a bug in gcs: please report it)",
                    )
                }
            }
        }
        (_, "/" | "/index.html" | "/style.css" | "/app.js" | "/api/model") => {
            Reply::error(405, "use GET")
        }
        (_, "/api/check" | "/api/solve" | "/api/compile") => Reply::error(405, "use POST"),
        _ => Reply::error(
            404,
            "not found: this server serves its page and its API only",
        ),
    }
}

/// The request's body, at most [`MAX_BODY`] bytes; else the 413 to answer.
fn read_body(request: &mut tiny_http::Request) -> Result<Vec<u8>, Reply> {
    let too_large = || Reply::error(413, &format!("the request body is over {MAX_BODY} bytes"));
    if request.body_length().is_some_and(|n| n > MAX_BODY) {
        return Err(too_large());
    }
    let mut body = Vec::new();
    let limit = MAX_BODY as u64 + 1;
    match request.as_reader().take(limit).read_to_end(&mut body) {
        Ok(n) if n > MAX_BODY => Err(too_large()),
        Ok(_) => Ok(body),
        Err(e) => Err(Reply::error(400, &format!("cannot read the request: {e}"))),
    }
}

/// Whether the request may be answered: a server bound to a loopback address answers only
/// requests addressed to a loopback name (`127.0.0.1`, `localhost`, `[::1]`), so that a page of
/// another site, whose name was pointed at this machine, cannot read the model through it.
fn host_allowed(bound: SocketAddr, request: &tiny_http::Request) -> bool {
    if !bound.ip().is_loopback() {
        return true;
    }
    let Some(host) = request
        .headers()
        .iter()
        .find(|h| h.field.equiv("Host"))
        .map(|h| h.value.as_str().to_ascii_lowercase())
    else {
        // HTTP/1.0 clients may send none; they cannot have been sent by a browser elsewhere.
        return true;
    };
    let name = match host.strip_prefix('[') {
        Some(v6) => v6.split(']').next().unwrap_or(""),
        None => host.split(':').next().unwrap_or(""),
    };
    name == "localhost"
        || name.ends_with(".localhost")
        || name.parse::<IpAddr>().is_ok_and(|ip| ip.is_loopback())
}
