//! `gcs serve`: the server's limits over the network, and the page in a real browser.
//!
//! The browser tests drive Debian's headless Chromium through chromedriver (WebDriver, with
//! fantoccini). When `/usr/bin/chromium` or `/usr/bin/chromedriver` is missing they run
//! `.ci/install-browser` first, and fail, saying so, if the browser is still missing: they are
//! never skipped.
//!
//! The four-bar's steps: drag the crank slider and check that the drawn coupler point, mapped
//! back from the SVG's pixels through the fit the page was given, is where `gcs solve --json`
//! puts it at the slider's value; flip `elbow` and check the other assembly the same way; trace
//! the coupler curve; make the four-bar fail to close and see the failure in `gcs solve`'s
//! words with the picture marked as not current; type a syntax error and see its located
//! diagnostic, as `gcs check` prints it; fix it and see the mechanism again; show the Rust
//! module, as `gcs compile` writes it; and on the way, the live socket closed, the page solving
//! by POSTs instead. The Jansen leg's: drag its crank slider over several values, each drag
//! redrawing, solved on the live socket, and print the page's own solve-and-draw timings (run
//! with `--nocapture` to see them; no test asserts a speed). The live socket is also driven over
//! a plain socket: it solves as `/api/solve` does, for the server's own page only. With `GCS_SERVE_SCREENSHOTS=DIR`, the
//! page is saved as a PNG in DIR at each step.

use fantoccini::actions::{InputSource, MouseActions, PointerAction, MOUSE_BUTTON_LEFT};
use fantoccini::key::Key;
use fantoccini::{Client, ClientBuilder, Locator};
use serde_json::{json, Value};
use std::io::{BufRead as _, BufReader, Read as _, Write as _};
use std::net::{SocketAddr, TcpStream};
use std::os::unix::process::CommandExt as _;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};
use support::{gcs, gcs_in, root};

mod support;

/// `gcs solve --json ARGS`'s point `name`.
fn solved_point(file: &str, args: &[&str], name: &str) -> [f64; 2] {
    let mut all = vec!["solve", file, "--json"];
    all.extend(args);
    let (code, out, err) = gcs(&all);
    assert_eq!(code, 0, "gcs {all:?}: {err}");
    let v: Value = serde_json::from_str(&out).expect("gcs solve --json prints JSON");
    let p = &v["points"][name];
    [p[0].as_f64().expect("x"), p[1].as_f64().expect("y")]
}

/// A running `gcs serve FILE --port 0`, stopped when dropped.
struct Served {
    child: Child,
    url: String,
    addr: SocketAddr,
}

impl Served {
    fn start(file: &str) -> Served {
        let mut child = Command::new(env!("CARGO_BIN_EXE_gcs"))
            .current_dir(root())
            .args(["serve", file, "--port", "0"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start gcs serve");
        let mut line = String::new();
        let stdout = child.stdout.take().expect("stdout");
        BufReader::new(stdout)
            .read_line(&mut line)
            .expect("gcs serve prints its URL");
        let url = line.trim().to_string();
        let addr = url
            .strip_prefix("http://")
            .and_then(|rest| rest.strip_suffix('/'))
            .and_then(|a| a.parse().ok())
            .unwrap_or_else(|| panic!("the first line is the URL, not {line:?}"));
        assert!(url.starts_with("http://127.0.0.1:"), "{url}");
        Served { child, url, addr }
    }

    /// Whether the server is still running.
    fn alive(&mut self) -> bool {
        matches!(self.child.try_wait(), Ok(None))
    }

    /// Sends `head` (a request line and headers, without the blank line) and `body`; the
    /// status and body of the answer.
    fn raw(&self, head: &str, body: &[u8]) -> (u16, String) {
        let mut s = TcpStream::connect(self.addr).expect("connect");
        s.set_read_timeout(Some(Duration::from_secs(30)))
            .expect("timeout");
        let mut request = format!("{head}\r\nConnection: close\r\n\r\n").into_bytes();
        request.extend_from_slice(body);
        s.write_all(&request).expect("send");
        let mut answer = Vec::new();
        s.read_to_end(&mut answer).expect("read");
        let answer = String::from_utf8_lossy(&answer).into_owned();
        let status = answer
            .split(' ')
            .nth(1)
            .and_then(|c| c.parse().ok())
            .unwrap_or_else(|| panic!("no status in {answer:?}"));
        let body = answer
            .split_once("\r\n\r\n")
            .map_or("", |(_, b)| b)
            .to_string();
        (status, body)
    }

    fn get(&self, path: &str) -> (u16, String) {
        self.raw(&format!("GET {path} HTTP/1.1\r\nHost: {}", self.addr), b"")
    }

    fn post(&self, path: &str, body: &[u8]) -> (u16, String) {
        let head = format!(
            "POST {path} HTTP/1.1\r\nHost: {}\r\nContent-Type: application/json\r\nContent-Length: {}",
            self.addr,
            body.len()
        );
        self.raw(&head, body)
    }
}

impl Drop for Served {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

#[test]
fn the_server_serves_its_page_and_api_and_nothing_else() {
    let mut s = Served::start("examples/fourbar.gcs");
    let (code, html) = s.get("/");
    assert_eq!(code, 200);
    assert!(html.contains("<script src=\"/app.js\""), "{html}");
    for path in ["/style.css", "/app.js"] {
        assert_eq!(s.get(path).0, 200, "{path}");
    }
    let (code, model) = s.get("/api/model");
    assert_eq!(code, 200);
    let model: Value = serde_json::from_str(&model).expect("JSON");
    let text = std::fs::read_to_string(root().join("examples/fourbar.gcs")).expect("read");
    assert_eq!(model["text"], text.as_str());
    assert_eq!(model["name"], "examples/fourbar.gcs");
    // No file but the model is ever served, however the path is written.
    for path in [
        "/Cargo.toml",
        "/../Cargo.toml",
        "/%2e%2e/Cargo.toml",
        "/examples/fourbar.gcs",
        "//etc/passwd",
        "/app.js/../../Cargo.toml",
        "/api/nothing",
    ] {
        assert_eq!(s.get(path).0, 404, "{path}");
    }
    assert_eq!(s.get("/api/check").0, 405);
    // Another name for this machine is refused: a page of another site cannot reach it.
    let (code, _) = s.raw("GET / HTTP/1.1\r\nHost: example.com", b"");
    assert_eq!(code, 403);
    assert_eq!(s.raw("GET / HTTP/1.1\r\nHost: localhost:1", b"").0, 200);
    // A body over a mebibyte is refused before it is read; a body that is not JSON is a 400.
    let head = format!(
        "POST /api/check HTTP/1.1\r\nHost: {}\r\nContent-Length: {}",
        s.addr,
        2 << 20
    );
    let (code, body) = s.raw(&head, b"");
    assert_eq!(code, 413, "{body}");
    assert_eq!(s.post("/api/check", b"{\"text\": ").0, 400);
    assert_eq!(s.post("/api/solve", b"[1, 2]").0, 400);
    // A model that does not parse is answered with its located diagnostic...
    let bad = json!({ "text": "space 2d;\nfixed point A = (0, 0;\n" }).to_string();
    let (code, body) = s.post("/api/solve", bad.as_bytes());
    assert_eq!(code, 200);
    let v: Value = serde_json::from_str(&body).expect("JSON");
    assert_eq!(
        (v["ok"].as_bool(), v["stage"].as_str()),
        (Some(false), Some("model"))
    );
    assert_eq!(v["diagnostics"][0]["start"][0], 2, "{v}");
    // ... and the server goes on: the four-bar still solves, at the value asked.
    assert!(s.alive());
    let ok = json!({ "text": text, "set": ["theta=75deg"] }).to_string();
    let (code, body) = s.post("/api/solve", ok.as_bytes());
    assert_eq!(code, 200);
    let v: Value = serde_json::from_str(&body).expect("JSON");
    assert_eq!(v["ok"], true, "{v}");
    let want = solved_point(
        "examples/fourbar.gcs",
        &["--set", "theta=75deg"],
        "coupler.c",
    );
    assert_eq!(v["solution"]["points"]["coupler.c"], json!(want));
    assert!(s.alive());
}

/// A WebSocket client's end of `/api/live`, over a plain socket.
struct Live {
    stream: TcpStream,
}

impl Live {
    /// Opens `/api/live` with `extra` headers (an `Origin`, say): the socket, or the status and
    /// body of the refusal.
    fn open(s: &Served, extra: &str) -> Result<Live, (u16, String)> {
        let mut stream = TcpStream::connect(s.addr).expect("connect");
        stream
            .set_read_timeout(Some(Duration::from_secs(30)))
            .expect("timeout");
        let head = format!(
            "GET /api/live HTTP/1.1\r\nHost: {}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\
             Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n{extra}\r\n",
            s.addr
        );
        stream.write_all(head.as_bytes()).expect("send");
        let mut answer = Vec::new();
        let mut byte = [0u8; 1];
        while !answer.ends_with(b"\r\n\r\n") {
            stream.read_exact(&mut byte).expect("the answer's head");
            answer.push(byte[0]);
        }
        let answer = String::from_utf8_lossy(&answer).into_owned();
        let status: u16 = answer
            .split(' ')
            .nth(1)
            .and_then(|c| c.parse().ok())
            .unwrap_or_else(|| panic!("no status in {answer:?}"));
        if status != 101 {
            let mut body = String::new();
            let _ = stream.read_to_string(&mut body);
            return Err((status, body));
        }
        // The RFC's example key, and its answer.
        assert!(
            answer.contains("Sec-WebSocket-Accept: s3pPLMBiTxaQ9kYGzzhZRbK+xOo=\r\n"),
            "{answer}"
        );
        Ok(Live { stream })
    }

    /// Sends one text message, masked as a browser masks it.
    fn send(&mut self, text: &[u8]) {
        let mask = [0x12, 0x34, 0x56, 0x78];
        let mut frame = vec![0x81];
        match text.len() {
            n if n < 126 => frame.push(0x80 | n as u8),
            n if n <= 0xFFFF => {
                frame.push(0x80 | 126);
                frame.extend_from_slice(&(n as u16).to_be_bytes());
            }
            n => {
                frame.push(0x80 | 127);
                frame.extend_from_slice(&(n as u64).to_be_bytes());
            }
        }
        frame.extend_from_slice(&mask);
        frame.extend(text.iter().enumerate().map(|(k, b)| b ^ mask[k % 4]));
        // A peer that closed may refuse the rest: what it said is read next.
        let _ = self.stream.write_all(&frame);
    }

    /// The next frame: its opcode and payload.
    fn read(&mut self) -> (u8, Vec<u8>) {
        let mut head = [0u8; 2];
        self.stream.read_exact(&mut head).expect("a frame");
        assert_eq!(head[1] & 0x80, 0, "the server does not mask");
        let len = match head[1] {
            126 => {
                let mut b = [0u8; 2];
                self.stream.read_exact(&mut b).expect("length");
                usize::from(u16::from_be_bytes(b))
            }
            127 => {
                let mut b = [0u8; 8];
                self.stream.read_exact(&mut b).expect("length");
                u64::from_be_bytes(b) as usize
            }
            n => usize::from(n),
        };
        let mut payload = vec![0u8; len];
        self.stream.read_exact(&mut payload).expect("the payload");
        (head[0] & 0x0F, payload)
    }

    /// The answer to one message: `{"status", "answer"}`.
    fn ask(&mut self, text: &[u8]) -> Value {
        self.send(text);
        let (opcode, payload) = self.read();
        assert_eq!(opcode, 1, "a text message");
        serde_json::from_slice(&payload).expect("JSON")
    }
}

#[test]
fn the_live_socket_solves_for_the_servers_own_page_only() {
    let mut s = Served::start("examples/fourbar.gcs");
    let text = std::fs::read_to_string(root().join("examples/fourbar.gcs")).expect("read");
    // A page of another origin may not open it; nor may a plain GET, nor a POST.
    let refused = Live::open(&s, "Origin: http://example.com\r\n").err();
    assert_eq!(refused.map(|r| r.0), Some(403));
    let refused = Live::open(
        &s,
        &format!("Origin: http://localhost:{}\r\n", s.addr.port() + 1),
    );
    assert_eq!(refused.err().map(|r| r.0), Some(403));
    assert_eq!(s.get("/api/live").0, 426);
    assert_eq!(s.post("/api/live", b"{}").0, 405);
    // The page's own origin may: each message is a solve, answered as `/api/solve` answers it.
    let own = format!("Origin: http://{}\r\n", s.addr);
    let mut live = Live::open(&s, &own).expect("the page's own origin");
    for theta in ["75deg", "120deg"] {
        let set = format!("theta={theta}");
        let v = live.ask(json!({ "text": text, "set": [set] }).to_string().as_bytes());
        assert_eq!(v["status"], 200, "{v}");
        assert_eq!(v["answer"]["ok"], true, "{v}");
        let want = solved_point("examples/fourbar.gcs", &["--set", &set], "coupler.c");
        assert_eq!(v["answer"]["solution"]["points"]["coupler.c"], json!(want));
    }
    // A request that is not one is answered as the POST is, and the socket goes on.
    let v = live.ask(b"[1, 2]");
    assert_eq!(v["status"], 400, "{v}");
    let v = live.ask(json!({ "text": "space 2d; (((" }).to_string().as_bytes());
    assert_eq!(
        (v["status"].as_u64(), v["answer"]["stage"].as_str()),
        (Some(200), Some("model"))
    );
    // A message over a mebibyte closes the socket (1009, too large); the server goes on, and
    // a client that is not a browser (no `Origin`) is served too.
    let (opcode, payload) = {
        live.send(&vec![b' '; (1 << 20) + 1]);
        live.read()
    };
    assert_eq!((opcode, &payload[..2]), (8, &1009u16.to_be_bytes()[..]));
    assert!(s.alive());
    let mut again = Live::open(&s, "").expect("a client that is not a browser");
    let v = again.ask(json!({ "text": text }).to_string().as_bytes());
    assert_eq!(v["answer"]["ok"], true, "{v}");
    assert!(s.alive());
}

#[test]
fn serve_refuses_what_it_cannot_serve() {
    let (code, _, err) = gcs(&["serve", "examples/no_such_model.gcs", "--port", "0"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("cannot read `examples/no_such_model.gcs`"),
        "{err}"
    );
    let (code, _, err) = gcs(&["serve", "examples/fourbar.gcs", "--host", "nowhere"]);
    assert_eq!(code, 2);
    assert!(err.contains("`--host nowhere`: not an IP address"), "{err}");
}

// ---- the browser ------------------------------------------------------------------------------

const CHROMIUM: &str = "/usr/bin/chromium";
const CHROMEDRIVER: &str = "/usr/bin/chromedriver";

/// Chromium and chromedriver, installed by `.ci/install-browser` when missing (once for the
/// tests of this file); a test that still lacks them fails, saying what to do.
fn browser_installed() {
    static INSTALL: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _one_at_a_time = INSTALL.lock().unwrap_or_else(|e| e.into_inner());
    let present = || Path::new(CHROMIUM).exists() && Path::new(CHROMEDRIVER).exists();
    if !present() {
        let script = root().join(".ci/install-browser");
        eprintln!(
            "{CHROMIUM} or {CHROMEDRIVER} is missing: running {}",
            script.display()
        );
        let status = Command::new("bash").arg(&script).status();
        eprintln!("{} exited: {status:?}", script.display());
    }
    assert!(
        present(),
        "the browser tests need headless Chromium and chromedriver ({CHROMIUM}, {CHROMEDRIVER}): \
         `.ci/install-browser` could not install them (it runs `apt-get install chromium \
         chromium-driver`, as root or through sudo); install them and run the tests again"
    );
}

/// A headless Chromium driven by its own chromedriver, both stopped when dropped.
struct Browser {
    driver: Child,
    client: Client,
    _profile: tempfile::TempDir,
}

impl Browser {
    async fn start() -> Browser {
        browser_installed();
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .expect("a free port")
            .port();
        // Its own process group, with the browsers it starts: all are stopped together.
        let driver = Command::new(CHROMEDRIVER)
            .arg(format!("--port={port}"))
            .process_group(0)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start chromedriver");
        let profile = tempfile::tempdir().expect("a profile folder");
        let until = Instant::now() + Duration::from_secs(30);
        while TcpStream::connect(("127.0.0.1", port)).is_err() {
            assert!(
                Instant::now() < until,
                "chromedriver does not listen on {port}"
            );
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        let args = [
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-dev-shm-usage",
            "--window-size=1400,1000",
        ]
        .map(String::from)
        .into_iter()
        .chain([format!("--user-data-dir={}", profile.path().display())])
        .collect::<Vec<_>>();
        let mut caps = serde_json::Map::new();
        caps.insert(
            "goog:chromeOptions".to_string(),
            json!({ "binary": CHROMIUM, "args": args }),
        );
        let client = ClientBuilder::new(hyper_util::client::legacy::connect::HttpConnector::new())
            .capabilities(caps)
            .connect(&format!("http://127.0.0.1:{port}"))
            .await
            .expect("a session of headless Chromium");
        Browser {
            driver,
            client,
            _profile: profile,
        }
    }

    /// Runs `script` (a function body, its arguments in `arguments`) in the page.
    async fn js(&self, script: &str, args: Vec<Value>) -> Value {
        self.client
            .execute(script, args)
            .await
            .unwrap_or_else(|e| panic!("{script}: {e}"))
    }

    /// Waits (30 s at most) until `script` returns true; `what` says what for.
    async fn until(&self, what: &str, script: &str, args: Vec<Value>) {
        let until = Instant::now() + Duration::from_secs(30);
        loop {
            if self.js(script, args.clone()).await == Value::Bool(true) {
                return;
            }
            if Instant::now() > until {
                let state = self
                    .js(
                        "return [document.getElementById('drawing').dataset, \
                         document.getElementById('drawing-status').textContent, \
                         document.getElementById('check-status').textContent]",
                        vec![],
                    )
                    .await;
                panic!("waited 30 s {what}; the page: {state}");
            }
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
    }

    /// The drawing's state: `current`, `failed`, `stale` or `empty`, and how many drawings
    /// the page has made.
    async fn drawing(&self) -> (String, u64) {
        let v = self
            .js(
                "const d = document.getElementById('drawing'); \
                 return [d.dataset.state, Number(d.dataset.draws)]",
                vec![],
            )
            .await;
        (
            v[0].as_str().unwrap_or("").to_string(),
            v[1].as_u64().unwrap_or(0),
        )
    }

    /// Waits for a drawing after `draws` that is current and was asked with `set` among its
    /// params and `branch` among its branches (`NAME=VALUE` as the page sends them).
    async fn redrawn(&self, draws: u64, set: &str, branch: &str) {
        self.until(
            &format!("for a drawing after the {draws}th at {set} {branch}"),
            "const d = document.getElementById('drawing'); \
             return d.dataset.state === 'current' && Number(d.dataset.draws) > arguments[0] \
                 && (d.dataset.set || '').split(' ').includes(arguments[1]) \
                 && (arguments[2] === '' || (d.dataset.branch || '').split(' ').includes(arguments[2]))",
            vec![json!(draws), json!(set), json!(branch)],
        )
        .await;
    }

    /// Drags a range slider's thumb from `from` to `to`, fractions of its width, through a
    /// few pointer moves; the slider's value after the drag.
    async fn drag(&self, id: &str, from: f64, to: f64) -> String {
        let slider = self.id(id).await;
        let (x, y, w, h) = slider.rectangle().await.expect("the slider's place");
        let at = |f: f64| x + 8.0 + f * (w - 16.0);
        let mouse = MouseActions::new("mouse".to_string())
            .then(PointerAction::MoveTo {
                duration: None,
                x: at(from).round(),
                y: (y + h / 2.0).round(),
            })
            .then(PointerAction::Down {
                button: MOUSE_BUTTON_LEFT,
            })
            .then(PointerAction::MoveTo {
                duration: Some(Duration::from_millis(120)),
                x: at((from + to) / 2.0).round(),
                y: (y + h / 2.0).round(),
            })
            .then(PointerAction::MoveTo {
                duration: Some(Duration::from_millis(120)),
                x: at(to).round(),
                y: (y + h / 2.0).round(),
            })
            .then(PointerAction::Up {
                button: MOUSE_BUTTON_LEFT,
            });
        self.client
            .perform_actions(mouse)
            .await
            .expect("drag the slider");
        slider
            .prop("value")
            .await
            .expect("the slider's value")
            .unwrap_or_default()
    }

    /// Where the page drew point `name`, in the model's coordinates: the dot's pixel mapped
    /// back through the fit the page was given (`data-scale`, `data-corner-x`,
    /// `data-corner-y`); and the fit's scale, in pixels a unit.
    async fn drawn_point(&self, name: &str) -> ([f64; 2], f64) {
        let v = self
            .js(
                "const d = document.getElementById('drawing'); \
                 const c = d.querySelector(`svg circle.point[data-name=\"${arguments[0]}\"]`); \
                 if (!c) return null; \
                 return [Number(c.getAttribute('cx')), Number(c.getAttribute('cy')), \
                         Number(d.dataset.scale), Number(d.dataset.cornerX), Number(d.dataset.cornerY)]",
                vec![json!(name)],
            )
            .await;
        let n = |k: usize| {
            v[k].as_f64()
                .unwrap_or_else(|| panic!("no dot {name}: {v}"))
        };
        let (cx, cy, scale, x0, y0) = (n(0), n(1), n(2), n(3), n(4));
        ([x0 + cx / scale, y0 - cy / scale], scale)
    }

    /// Saves a screenshot of the page as `NAME.png` in the folder `GCS_SERVE_SCREENSHOTS`
    /// names, when it names one: the page as a person sees it at each step.
    async fn shot(&self, name: &str) {
        let Some(dir) = std::env::var_os("GCS_SERVE_SCREENSHOTS") else {
            return;
        };
        let png = self.client.screenshot().await.expect("a screenshot");
        let path = Path::new(&dir).join(format!("{name}.png"));
        std::fs::write(&path, png).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }

    /// The element with this id.
    async fn id(&self, id: &str) -> fantoccini::elements::Element {
        self.client
            .find(Locator::Id(id))
            .await
            .unwrap_or_else(|e| panic!("#{id}: {e}"))
    }

    async fn click(&self, id: &str) {
        self.id(id)
            .await
            .click()
            .await
            .unwrap_or_else(|e| panic!("click #{id}: {e}"));
    }

    async fn text(&self, id: &str) -> String {
        self.js(
            "return document.getElementById(arguments[0]).textContent",
            vec![json!(id)],
        )
        .await
        .as_str()
        .unwrap_or("")
        .to_string()
    }

    /// Ends the session (the browser quits), then the driver.
    async fn close(self) {
        let _ = self.client.clone().close().await;
    }
}

impl Drop for Browser {
    /// Stops chromedriver and every browser process it started (its process group), also
    /// when a test failed before `close`.
    fn drop(&mut self) {
        let group = format!("-{}", self.driver.id());
        let _ = Command::new("kill")
            .args(["-KILL", "--", &group])
            .stderr(Stdio::null())
            .status();
        let _ = self.driver.wait();
    }
}

/// The drawn point is where `gcs solve` puts it, to the SVG's rounding: the drawing writes
/// pixels with three decimals, half a thousandth of a pixel at most from the exact pixel, so
/// each coordinate is within `0.0005 / scale` model units (and a hair for the float
/// arithmetic of the mapping back).
fn assert_drawn_at(drawn: [f64; 2], scale: f64, want: [f64; 2], what: &str) {
    let tolerance = 0.0005 / scale + 1e-9;
    for k in 0..2 {
        assert!(
            (drawn[k] - want[k]).abs() <= tolerance,
            "{what}: drawn at {drawn:?}, solved at {want:?} (tolerance {tolerance:e})"
        );
    }
}

#[tokio::test]
async fn the_fourbar_page_moves_flips_traces_fails_and_checks_in_a_browser() {
    let served = Served::start("examples/fourbar.gcs");
    let b = Browser::start().await;
    let started = Instant::now();
    b.client.goto(&served.url).await.expect("open the page");
    b.until(
        "for the first drawing",
        "const d = document.getElementById('drawing'); \
         return d.dataset.state === 'current' && !!d.querySelector('svg circle.point')",
        vec![],
    )
    .await;
    println!("fourbar: page open and drawn in {:?}", started.elapsed());
    let slider = b
        .js(
            "const s = document.getElementById('param-theta'); return [s.min, s.max, s.value]",
            vec![],
        )
        .await;
    assert_eq!(
        slider,
        json!(["-150", "210", "30"]),
        "theta's slider: a turn about 30 deg"
    );

    // Drag the crank: the coupler point is drawn where `gcs solve` puts it at the slider's value.
    let (_, draws) = b.drawing().await;
    let theta = b.drag("param-theta", 0.5, 0.62).await;
    assert_ne!(theta, "30", "the drag moved the slider");
    let set = format!("theta={theta}deg");
    b.redrawn(draws, &set, "elbow=0").await;
    let (drawn, scale) = b.drawn_point("coupler.c").await;
    let want = solved_point("examples/fourbar.gcs", &["--set", &set], "coupler.c");
    assert_drawn_at(drawn, scale, want, &format!("coupler.c at {set}"));
    println!(
        "fourbar: crank dragged to {set}: coupler.c drawn at {drawn:?}, gcs solve {want:?}; {}",
        b.text("timing").await
    );

    // The drags were solved on the live socket. Closed (a server restarted, say), the page
    // POSTs its solves instead, and draws them the same.
    let via = "return document.getElementById('timing').dataset.via";
    assert_eq!(b.js(via, vec![]).await, "socket");
    b.js("live.socket.close()", vec![]).await;
    b.until(
        "for the live socket to close",
        "return live.socket === null",
        vec![],
    )
    .await;

    // Flip `elbow`: the other assembly, where `gcs solve --branch elbow=1` puts it.
    let elbow = b.id("branch-elbow").await;
    let labels = b
        .js(
            "return [...document.getElementById('branch-elbow').options].map(o => o.textContent)",
            vec![],
        )
        .await;
    assert_eq!(
        labels,
        json!([
            "0: rocker.c to the left of the line from crank.b to D (sketch)",
            "1: rocker.c to the right of the line from crank.b to D"
        ])
    );
    let (_, draws) = b.drawing().await;
    elbow.select_by_value("1").await.expect("choose elbow 1");
    b.redrawn(draws, &set, "elbow=1").await;
    let (flipped, scale) = b.drawn_point("coupler.c").await;
    let want = solved_point(
        "examples/fourbar.gcs",
        &["--set", &set, "--branch", "elbow=1"],
        "coupler.c",
    );
    assert_drawn_at(
        flipped,
        scale,
        want,
        &format!("coupler.c at {set}, elbow 1"),
    );
    assert!(
        (flipped[0] - drawn[0]).hypot(flipped[1] - drawn[1]) > 1.0,
        "the other assembly: {drawn:?} then {flipped:?}"
    );
    assert_eq!(b.js(via, vec![]).await, "http", "solved by a POST");
    b.shot("fourbar-1-elbow-flipped").await;
    println!("fourbar: elbow flipped: coupler.c drawn at {flipped:?}, gcs solve {want:?}");

    // Trace the coupler curve over theta's sweep.
    let (_, draws) = b.drawing().await;
    b.click("trace-coupler.c").await;
    b.until(
        "for the coupler curve",
        "const d = document.getElementById('drawing'); \
         return Number(d.dataset.draws) > arguments[0] && d.dataset.state === 'current' \
             && !!d.querySelector('svg g.trace[data-name=\"coupler.c\"] polyline')",
        vec![json!(draws)],
    )
    .await;
    b.shot("fourbar-2-traced").await;
    assert_eq!(
        b.text("sweep-status").await,
        "61 samples of theta, all solved."
    );
    let steps = b.id("sweep-steps").await;
    steps.clear().await.expect("clear");
    steps
        .send_keys(&format!("12{}", Key::Enter))
        .await
        .expect("type 12 steps");
    b.until(
        "for a sweep of 13 samples",
        "return document.getElementById('sweep-status').textContent \
             === '13 samples of theta, all solved.'",
        vec![],
    )
    .await;

    // A crank too long to close: the failure in `gcs solve`'s words, the picture not current.
    let (_, draws) = b.drawing().await;
    let field = b.id("param-crank_len-value").await;
    field.clear().await.expect("clear");
    field
        .send_keys(&format!("20{}", Key::Enter))
        .await
        .expect("type 20");
    b.until(
        "for the failure",
        "return document.getElementById('drawing').dataset.state === 'failed'",
        vec![],
    )
    .await;
    let (_, after) = b.drawing().await;
    assert_eq!(after, draws, "a failed solve draws nothing");
    let status = b.text("drawing-status").await;
    let (code, _, err) = gcs(&[
        "solve",
        "examples/fourbar.gcs",
        "--set",
        &set,
        "--set",
        "crank_len=20",
        "--branch",
        "elbow=1",
    ]);
    assert_eq!(code, 1);
    let said = err.lines().next().expect("gcs solve says why");
    assert!(said.starts_with("error: constraint `elbow`"), "{said}");
    assert!(
        status.contains(said),
        "the page says {status:?}, gcs solve {said:?}"
    );
    assert!(status.contains("the picture greyed below is the last that solved"));
    b.shot("fourbar-3-failed").await;
    println!("fourbar: crank_len=20 does not solve: {said}");
    field.clear().await.expect("clear");
    field
        .send_keys(&format!("1.5{}", Key::Enter))
        .await
        .expect("type 1.5");
    b.redrawn(draws, "crank_len=1.5", "elbow=1").await;

    // A syntax error typed in the editor: its located diagnostic, as `gcs check` prints it.
    let editor = b.id("editor").await;
    let original = b
        .js("return document.getElementById('editor').value", vec![])
        .await;
    editor.click().await.expect("focus the editor");
    b.js(
        "const e = document.getElementById('editor'); e.setSelectionRange(e.value.length, e.value.length)",
        vec![],
    )
    .await;
    let typed = "coincident(A, D;";
    editor.send_keys(typed).await.expect("type");
    b.until(
        "for the diagnostic",
        "return !!document.querySelector('#diagnostics li.error')",
        vec![],
    )
    .await;
    let broken = format!("{}{typed}", original.as_str().expect("text"));
    let dir = tempfile::tempdir().expect("a folder");
    std::fs::create_dir(dir.path().join("examples")).expect("mkdir");
    std::fs::write(dir.path().join("examples/fourbar.gcs"), &broken).expect("write");
    let (code, _, checked) = gcs_in(dir.path(), &["check", "examples/fourbar.gcs"]);
    assert_eq!(code, 1);
    let message = checked
        .lines()
        .next()
        .and_then(|l| l.strip_prefix("error: "))
        .expect("gcs check's message");
    let place = checked
        .lines()
        .find_map(|l| l.trim().strip_prefix("┌─ examples/fourbar.gcs:"))
        .expect("gcs check's place");
    let shown = b
        .js(
            "return document.querySelector('#diagnostics li.error').textContent",
            vec![],
        )
        .await;
    assert_eq!(shown, json!(format!("{place} error: {message}")));
    assert_eq!(
        b.text("rendered").await,
        checked,
        "the page renders what gcs check prints"
    );
    let (state, _) = b.drawing().await;
    assert_eq!(state, "stale", "the picture is not shown as current");
    b.shot("fourbar-4-syntax-error").await;
    println!("fourbar: typed {typed:?}: the page shows {shown}");

    // Fixed: the mechanism again.
    let (_, draws) = b.drawing().await;
    editor
        .send_keys(&Key::Backspace.to_string().repeat(typed.chars().count()))
        .await
        .expect("delete what was typed");
    b.redrawn(draws, &set, "elbow=1").await;
    assert_eq!(
        b.js("return document.getElementById('editor').value", vec![])
            .await,
        original
    );
    assert_eq!(b.text("diagnostics").await, "No diagnostics.");
    let (again, scale) = b.drawn_point("coupler.c").await;
    assert_drawn_at(again, scale, want, "coupler.c after the fix");

    // The Rust module, as `gcs compile` writes it, to show and download.
    b.click("compile").await;
    b.until(
        "for the module",
        "return document.getElementById('code-dialog').open && \
         document.getElementById('code').textContent.length > 0",
        vec![],
    )
    .await;
    b.shot("fourbar-5-module").await;
    let (_, module, _) = gcs(&["compile", "examples/fourbar.gcs"]);
    assert_eq!(b.text("code").await, module);
    let link = b
        .js(
            "const a = document.getElementById('code-download'); return [a.download, a.href.startsWith('blob:')]",
            vec![],
        )
        .await;
    assert_eq!(link, json!(["fourbar.rs", true]));
    b.close().await;
}

#[tokio::test]
async fn the_jansen_leg_redraws_at_each_drag_and_the_page_times_it() {
    let served = Served::start("examples/jansen_leg.gcs");
    let b = Browser::start().await;
    b.client.goto(&served.url).await.expect("open the page");
    b.until(
        "for the first drawing",
        "return document.getElementById('drawing').dataset.state === 'current'",
        vec![],
    )
    .await;
    let mut timings = Vec::new();
    let mut last = b.drawn_point("foot").await.0;
    let stops = [0.5, 0.58, 0.66, 0.74, 0.82, 0.9, 0.98, 0.1, 0.2, 0.3, 0.4];
    for pair in stops.windows(2) {
        let (_, draws) = b.drawing().await;
        let theta = b.drag("param-theta", pair[0], pair[1]).await;
        let set = format!("theta={theta}deg");
        b.redrawn(draws, &set, "").await;
        let timing = b.text("timing").await;
        let parts = b
            .js(
                "const t = document.getElementById('timing').dataset; \
                 return [Number(t.waited), Number(t.answered), Number(t.drawing), t.via]",
                vec![],
            )
            .await;
        let ms: f64 = b
            .js(
                "return Number(document.getElementById('timing').dataset.ms)",
                vec![],
            )
            .await
            .as_f64()
            .expect("the timing in ms");
        assert!(
            timing.starts_with("solved and drawn in ") && timing.ends_with(" ms"),
            "{timing}"
        );
        assert_eq!(
            parts[3], "socket",
            "the drag to {set} solved on the live socket"
        );
        let (foot, scale) = b.drawn_point("foot").await;
        assert!(foot != last, "the drag to {set} drew the foot elsewhere");
        let want = solved_point("examples/jansen_leg.gcs", &["--set", &set], "foot");
        assert_drawn_at(foot, scale, want, &format!("foot at {set}"));
        last = foot;
        println!(
            "jansen_leg: crank dragged to {set}: {timing} (waiting for the solve before {:.1} ms, \
             asking the server {:.1} ms on the live socket, drawing {:.1} ms)",
            parts[0].as_f64().unwrap_or(f64::NAN),
            parts[1].as_f64().unwrap_or(f64::NAN),
            parts[2].as_f64().unwrap_or(f64::NAN)
        );
        timings.push(ms);
    }
    b.shot("jansen-leg").await;
    timings.sort_by(f64::total_cmp);
    println!(
        "jansen_leg: {} drags, solved and drawn in {:.1} ms (median), {:.1} ms (fastest), {:.1} ms (slowest)",
        timings.len(),
        timings[timings.len() / 2],
        timings[0],
        timings[timings.len() - 1]
    );
    b.close().await;
}
