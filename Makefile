# glideplan: `make demo` and `make test` work on a fresh machine with only python3 and pip.
# `make install` builds .venv from requirements.lock (the versions CI tested); `make lock`
# regenerates the lock from pyproject.toml's ranges in a throw-away venv.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
LOCK := requirements.lock
EXTRAS := all,test,bench

.PHONY: install demo test test-setup test-suite lint typecheck warm-up bench validate lock clean

$(STAMP): pyproject.toml $(LOCK)
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	# --no-compile: Python compiles what is imported on first use; compiling every installed
	# module up front costs ~35 s of a fresh install (measured 61 s -> 27 s)
	$(BIN)/python -m pip install --quiet --no-compile -c $(LOCK) -e ".[$(EXTRAS)]"
	touch $(STAMP)

install: $(STAMP)

lock:
	rm -rf .lock-venv
	$(PYTHON) -m venv .lock-venv
	.lock-venv/bin/python -m pip install --quiet --upgrade pip
	.lock-venv/bin/python -m pip install --quiet -e ".[$(EXTRAS)]"
	.lock-venv/bin/python -m pip freeze --exclude-editable --all \
	  | grep -v -E '^(pip|setuptools|wheel)==' > $(LOCK)
	rm -rf .lock-venv
	@echo "wrote $(LOCK) ($$(wc -l < $(LOCK)) pins)"

demo: $(STAMP)
	MPLBACKEND=Agg $(BIN)/glideplan demo --out out

# System programs the tests read files back with or drive (Debian packages): installed with
# apt-get when missing and possible (CI runs as root); the tests that need them skip with the
# reason otherwise.
test-setup:
	@missing=""; \
	command -v gpsbabel >/dev/null 2>&1 || missing="$$missing gpsbabel"; \
	command -v chromium >/dev/null 2>&1 || missing="$$missing chromium"; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "installing$$missing with apt-get"; \
	    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing \
	      >/dev/null) || echo "warning: apt-get could not install$$missing"; \
	  else \
	    echo "note:$$missing missing and not installable here (not root or no apt-get)"; \
	  fi; \
	fi

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks examples

typecheck: $(STAMP)
	$(BIN)/mypy src

# Compile the numba kernels once, so that the two test workers load them from the cache
# instead of compiling them each (~65 s of CPU on a fresh checkout).
warm-up: $(STAMP)
	MPLBACKEND=Agg $(BIN)/glideplan warm-up --jobs 2

# mypy (one process, ~45 s of CPU) runs beside the warm-up and then beside the tests: it needs
# no kernels, and the test workers leave CPU idle while they wait for Chromium, servers and
# subprocesses. Waiting for it before the tests left a core idle at the end of the warm-up.
# (Its one line of output may land among pytest's dots.)
test: $(STAMP) test-setup lint
	$(MAKE) --no-print-directory -j2 typecheck test-suite

# The suite alone, after the warm-up. Two pytest workers keep both cores busy: numba's kernels
# run single-threaded inside them.
test-suite: warm-up
	MPLBACKEND=Agg NUMBA_NUM_THREADS=1 $(BIN)/python -m pytest -n 2 -q -m "not heavy"

bench: $(STAMP)
	MPLBACKEND=Agg $(BIN)/python benchmarks/run_all.py

validate: $(STAMP) test-setup
	MPLBACKEND=Agg NUMBA_NUM_THREADS=1 $(BIN)/python -m pytest -n 2 -q -m heavy
	MPLBACKEND=Agg $(BIN)/python benchmarks/run_all.py --validate

clean:
	rm -rf $(VENV) out .pytest_cache .ruff_cache .hypothesis .mypy_cache
