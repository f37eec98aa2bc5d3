"""Opens an sgapi-render --report folder in headless Chromium (Selenium) as a person would, and
checks it:
- the page is self-contained: no URL it names leaves the folder, and every file it names exists;
- the failing scenes are exactly the expected ones and come first;
- every image loads (naturalWidth > 0) once scrolled into view (they load lazily), the passing
  scenes' too once their section is opened;
- the switch view (shown instead of the side-by-side images) flips the shown image between
  expected and actual on a click, and the swipe slider moves the cut;
- the browser logs no console error.
Prints the page's load time (navigation start to the load event); --max-load-ms fails past it.
--screenshot saves the top of the page as a PNG.

    /usr/bin/python3 report_browser.py REPORT_DIR --failures A,B,C [--screenshot OUT.png]
                     [--max-load-ms MS]

Needs Debian's chromium, chromium-driver and python3-selenium (Debian's module loads in Debian's
/usr/bin/python3).
"""
import argparse
import html.parser
import os
import pathlib
import sys
import time
import urllib.parse

from selenium import webdriver
from selenium.webdriver.chrome.options import Options
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By


class Links(html.parser.HTMLParser):
    """Every URL the page names: src and href attributes."""

    def __init__(self):
        super().__init__()
        self.urls = []

    def handle_starttag(self, tag, attrs):
        for key, value in attrs:
            if key in ("src", "href", "data-expected", "data-actual") and value is not None:
                self.urls.append((tag, key, value))


def check_static(folder, page):
    parser = Links()
    parser.feed(page.read_text(encoding="utf-8"))
    for tag, key, url in parser.urls:
        parts = urllib.parse.urlsplit(url)
        if parts.scheme == "data":
            continue
        if parts.scheme or parts.netloc or url.startswith("/"):
            sys.exit(f"FAIL: <{tag} {key}={url!r}> leaves the report folder")
        path = folder / urllib.parse.unquote(parts.path)
        if not path.is_file():
            sys.exit(f"FAIL: <{tag} {key}={url!r}>: no file {path}")
    return len(parser.urls)


def start_browser(width, height):
    opts = Options()
    opts.binary_location = "/usr/bin/chromium"
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                f"--window-size={width},{height}", "--hide-scrollbars"):
        opts.add_argument(arg)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=opts)


def wait_for(driver, script, element, what, timeout=20):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if driver.execute_script(script, element):
            return
        time.sleep(0.02)
    sys.exit(f"FAIL: {what} (waited {timeout} s)")


LOADED = "return arguments[0].complete && arguments[0].naturalWidth > 0;"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("report")
    ap.add_argument("--failures", default="", help="the scenes that must be listed as failing")
    ap.add_argument("--screenshot")
    ap.add_argument("--max-load-ms", type=float)
    ap.add_argument("--width", type=int, default=1400)
    ap.add_argument("--height", type=int, default=1000)
    args = ap.parse_args()
    folder = pathlib.Path(args.report).resolve()
    page = folder / "index.html"
    urls = check_static(folder, page)
    expected_failures = {s for s in args.failures.split(",") if s}

    driver = start_browser(args.width, args.height)
    try:
        driver.get(page.as_uri())
        load_ms = driver.execute_script(
            "const n = performance.getEntriesByType('navigation')[0];"
            "return n.loadEventEnd - n.startTime;")
        print(f"load: {load_ms:.0f} ms (navigation start to load event), {urls} URLs")
        if args.screenshot:
            driver.save_screenshot(args.screenshot)
            print(f"screenshot: {args.screenshot}")

        scenes = driver.find_elements(By.CSS_SELECTOR, "article.scene")
        states = [(s.get_attribute("id")[len("scene-"):], "fail" in s.get_attribute("class"))
                  for s in scenes]
        failing = [name for name, failed in states if failed]
        if set(failing) != expected_failures:
            sys.exit(f"FAIL: failing scenes {sorted(failing)}, expected "
                     f"{sorted(expected_failures)}")
        if [failed for _, failed in states] != sorted((f for _, f in states), reverse=True):
            sys.exit(f"FAIL: the failures are not listed first: {states}")
        count = driver.find_element(By.ID, "failed-count").text
        if not count.startswith(f"{len(expected_failures)} failed"):
            sys.exit(f"FAIL: the header says {count!r}")

        # Every image, as a reader scrolling through would see it: passing scenes opened.
        driver.execute_script("const d = document.getElementById('passed'); if (d) d.open = true;")
        images = driver.find_elements(By.CSS_SELECTOR, "article.scene img")
        for img in images:
            driver.execute_script("arguments[0].scrollIntoView({block: 'center'});", img)
            wait_for(driver, LOADED, img, f"image {img.get_attribute('src')} did not load")
        print(f"images: {len(images)} loaded")

        # Switch: the shown image changes on a click, and back; on a failing scene when one has
        # both images, else on the first scene that has.
        both = [s for s in scenes if s.get_attribute("data-expected")]
        both.sort(key=lambda s: "fail" not in s.get_attribute("class"))
        if not both:
            sys.exit("FAIL: no scene with both an expected and an actual image")
        scene = both[0]
        driver.execute_script("const d = document.getElementById('passed'); if (d) d.open = true;")
        name = scene.get_attribute("id")[len("scene-"):]
        scene.find_element(By.CSS_SELECTOR, "button[data-mode=switch]").click()
        flip = scene.find_element(By.CSS_SELECTOR, "img.flip")
        if scene.find_element(By.CSS_SELECTOR, ".images").is_displayed():
            sys.exit(f"FAIL: {name}: the side-by-side images still show in the switch view")
        wait_for(driver, LOADED, flip, "the switch view's image did not load")
        before = flip.get_attribute("src")
        flip.click()
        wait_for(driver, LOADED, flip, "the switch view's second image did not load")
        after = flip.get_attribute("src")
        if before == after or not before.endswith(".expected.png") \
                or not after.endswith(".actual.png"):
            sys.exit(f"FAIL: {name}: switch shows {before}, then after a click {after}")
        flip.click()
        if flip.get_attribute("src") != before:
            sys.exit(f"FAIL: {name}: a second click does not flip back")
        print(f"switch: {name} flips {os.path.basename(before)} <-> {os.path.basename(after)}")

        # Swipe: the slider moves the cut between the two images.
        scene.find_element(By.CSS_SELECTOR, "button[data-mode=swipe]").click()
        slider = scene.find_element(By.CSS_SELECTOR, ".swipe + input[type=range]")
        top = scene.find_element(By.CSS_SELECTOR, ".swipe img.top")
        wait_for(driver, LOADED, top, "the swipe view's image did not load")
        driver.execute_script("arguments[0].value = 20;"
                              "arguments[0].dispatchEvent(new Event('input'));", slider)
        clip = driver.execute_script("return arguments[0].style.clipPath;", top)
        if "80%" not in clip:
            sys.exit(f"FAIL: {name}: the swipe slider at 20 gives clip-path {clip!r}")
        print(f"swipe: slider at 20 -> clip-path {clip}")
        scene.find_element(By.CSS_SELECTOR, "button[data-mode=side]").click()

        errors = [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]
        if errors:
            sys.exit("FAIL: console errors:\n" + "\n".join(e["message"] for e in errors))
        if args.max_load_ms is not None and load_ms > args.max_load_ms:
            sys.exit(f"FAIL: load took {load_ms:.0f} ms, more than {args.max_load_ms:.0f} ms")
    finally:
        driver.quit()
    print("report_browser: all checks passed")


if __name__ == "__main__":
    main()
