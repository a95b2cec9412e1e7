#!/usr/bin/env bash
# The comparison page in headless Chromium: the synthetic comparison's page (compare_page_fixture, built beside rtm)
# opens with no console error, every picture (those in the closed per-view grids too) and every plot (the flat
# base's 3 and each curved base's 3: the cylinder's and the sphere's) loads and draws, and a screenshot is written.
# The page records script errors and pictures that fail to load on <body>'s attributes (measure/compare_page.cpp),
# read back here from the DOM Chromium dumps. Skipped (exit 77) when /usr/bin/chromium is absent: scripts/setup.sh
# installs it.
. "$(dirname "$0")/lib.bash"

CHROMIUM=/usr/bin/chromium
if [ ! -x "$CHROMIUM" ]; then
  echo "SKIP: $CHROMIUM is absent (Debian package chromium; scripts/setup.sh installs it)"
  exit 77
fi
FIXTURE=$(dirname "$RTM")/compare_page_fixture
if ! "$FIXTURE" "$T/page" 2>"$T/fixture.err"; then
  echo "FAIL: $FIXTURE $T/page: $(cat "$T/fixture.err")"
  exit 1
fi

url="file://$T/page/index.html"
# Root needs --no-sandbox; a profile of our own so no other Chromium's state is touched. The virtual time budget
# lets the load event fire before the DOM is dumped.
browse() {
  timeout 60 "$CHROMIUM" --headless=new --no-sandbox --disable-gpu --no-first-run --disable-extensions \
    --user-data-dir="$T/profile" --enable-logging=stderr --v=0 "$@" "$url"
}
browse --virtual-time-budget=10000 --dump-dom >"$T/dom.html" 2>"$T/chromium.log"
status=$?
body=$(grep -o '<body[^>]*>' "$T/dom.html" | head -1)
attr() { sed -n "s/.* $1=\"\\([^\"]*\\)\".*/\\1/p" <<<"$body"; }
check() {  # check DESCRIPTION CONDITION...
  local what=$1
  shift
  if "$@"; then passes=$((passes + 1)); else echo "FAIL: $what"; fails=$((fails + 1)); fi
}
check "chromium --dump-dom exited $status" [ "$status" = 0 ]
check "the page's load handler ran (body: $body)" [ "$(attr data-status)" = ready ]
check "no script error or failed picture: $(sed -n '/<pre id="page-errors">/,/<\/pre>/p' "$T/dom.html" | head -5)" \
  [ "$(attr data-errors)" = 0 ]
check "every picture loaded ($(attr data-images-loaded) of $(attr data-images))" \
  [ "$(attr data-images)" = 173 -a "$(attr data-images-loaded)" = 173 ]
check "every plot drawn ($(attr data-plots-drawn) of $(attr data-plots))" \
  [ "$(attr data-plots)" = 9 -a "$(attr data-plots-drawn)" = 9 ]
check "one point per method id in each of the 9 plots ($(attr data-plot-points))" [ "$(attr data-plot-points)" = 27 ]
console=$(grep -E 'CONSOLE|Uncaught' "$T/chromium.log" | head -5)
check "no console message: $console" [ -z "$console" ]

browse --screenshot="$T/page.png" --window-size=1280,1600 >/dev/null 2>"$T/shot.log"
check "a screenshot is written: $(tail -2 "$T/shot.log")" [ -s "$T/page.png" ]
if [ -n "${RTM_KEEP_SCREENSHOT:-}" ]; then cp "$T/page.png" "$RTM_KEEP_SCREENSHOT"; fi
finish
