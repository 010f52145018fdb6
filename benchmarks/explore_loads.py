"""Benchmark: fresh loads of every explorer mode, and tabs that compute at the same moment.

Issue 27's checks, longer than the test suite allows: N fresh loads (default 10) of every mode
(the plane planners, the slow direct ones, route, mission, reach), opened at once in one
Chromium (Playwright) against a server in this process. For each load: whenever the strip
says `solved`, the answer's data sources (`gp-answer`) in the browser must be non-empty; page
errors and console errors are counted. Then 2 and 4 tabs open the route and reach links at
once: every tab must show an answer, and the server must still serve a page afterwards.

Usage: python benchmarks/explore_loads.py [--loads N] [--modes dubins route ...]
"""

from __future__ import annotations

import argparse
import socket
import sys
import time
import urllib.request

CHROMIUM = "/usr/bin/chromium"
ROUTE = "planner=route&example=double-gyre&from=30.2,-39.8&to=30.7,-38.3&speed=1&resolution=3000"
REACH = "planner=reach&example=ridge&from=46.5,7.4,1800&wind=4,250&mc=0&safety=300"
MODES = {
    "dubins": "planner=dubins&goal=4,3,90&radius=1",
    "wind": "planner=wind&goal=4,-2,135&speed=1&radius=1&wind=0.5,30",
    "time-optimal": "planner=time-optimal&goal=0.5,1.5,200&v_min=0.3&v_max=1&u_max=1",
    "min-altitude": "planner=min-altitude&goal=300,-250,180",
    "min-altitude-direct": "planner=min-altitude-direct&goal=300,-250,180",
    "load-factor": "planner=load-factor&goal=3,2,60",
    "route": ROUTE,
    "mission": "planner=mission",
    "reach": REACH,
}
ANSWER_JS = """() => { const out = [];
  for (const d of Bokeh.documents) for (const m of d.all_models)
    if (m.name === 'gp-answer') { const k = Object.keys(m.data)[0];
      out.push(k ? m.data[k].length : 0); }
  return out; }"""


def _settled(page, timeout=180.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if page.locator(".gp-status").count() and not page.locator(".gp-busy").count():
            status = page.locator(".gp-status").first.inner_text().strip()
            if status:
                return status
        time.sleep(0.2)
    return "(no answer)"


def _load(ctx, urls):
    errors: list[str] = []
    pages = []
    for _ in urls:
        page = ctx.new_page()
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
        pages.append(page)
    for page, url in zip(pages, urls, strict=True):
        page.goto(url, wait_until="commit")
    out = []
    for page in pages:
        status = _settled(page)
        page.wait_for_timeout(300)
        out.append((status, page.evaluate(ANSWER_JS)))
        page.close()
    return out, errors


def main() -> int:
    from playwright.sync_api import sync_playwright

    from glideplan.explore.server import serve

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--loads", type=int, default=10)
    ap.add_argument("--modes", nargs="*", default=list(MODES))
    args = ap.parse_args()
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = int(s.getsockname()[1])
    srv = serve(port, "127.0.0.1", show=False, threaded=True)
    time.sleep(2.0)
    base = f"http://127.0.0.1:{port}/?"
    failed = 0
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM,
                                    args=["--no-sandbox", "--disable-gpu"])
        ctx = browser.new_context(viewport={"width": 1200, "height": 850})
        print("mode                 loads  solved  empty-when-solved  script errors  seconds")
        for mode in args.modes:
            t0 = time.perf_counter()
            res, errors = _load(ctx, [base + MODES[mode]] * args.loads)
            solved = [r for r in res if r[0].startswith("solved")]
            empty = sum(1 for _, lens in solved if not lens or min(lens) == 0)
            script = [e for e in errors if "Failed to load resource" not in e]
            failed += empty + len(script)
            print(f"{mode:20s} {args.loads:5d} {len(solved):7d} {empty:18d} {len(script):14d}"
                  f"  {time.perf_counter() - t0:7.1f}")
        for tabs in (2, 4):
            t0 = time.perf_counter()
            urls = [base + (ROUTE if i % 2 == 0 else REACH) for i in range(tabs)]
            res, _ = _load(ctx, urls)
            with urllib.request.urlopen(base + "planner=dubins", timeout=30) as r:
                alive = r.status == 200
            answered = sum(1 for st, _ in res if st.startswith("solved"))
            failed += (answered != tabs) + (not alive)
            print(f"{tabs} tabs route+reach at once: {answered}/{tabs} solved, server alive: "
                  f"{alive}, {time.perf_counter() - t0:.1f} s")
        browser.close()
    srv.stop()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
