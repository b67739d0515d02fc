# factask: the two commands a newcomer needs are `make demo` and `make test`.
# Both create .venv if missing, install the project and what it needs (system
# rendering libraries too), then run.

PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed
# Debian packages for headless rendering (EGL software renderer, OSMesa fallback).
SYSTEM_PACKAGES := libegl1 libegl-mesa0 libgl1-mesa-dri libosmesa6
export MUJOCO_GL ?= egl
export LITELLM_LOCAL_MODEL_COST_MAP := True

.PHONY: setup system-deps demo test test-fast lint bench clean

setup: $(STAMP)

system-deps:
	@if ! command -v dpkg >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then \
	  echo "not a Debian system: install the headless GL libraries yourself (EGL with"; \
	  echo "Mesa, or OSMesa; on Debian: $(SYSTEM_PACKAGES)) and pick MUJOCO_GL=egl or"; \
	  echo "MUJOCO_GL=osmesa. Going on: everything but rendering works without them."; \
	  exit 0; \
	fi; \
	missing=""; for p in $(SYSTEM_PACKAGES); do \
	  dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing system packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing; \
	fi

$(STAMP): pyproject.toml
	@$(MAKE) --no-print-directory system-deps
	@test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -e ".[dev,gpu]"
	@touch $(STAMP)

demo: $(STAMP)
	$(PY) -m factask demo --out out/demo

# The whole suite, the arm sweeps (marked slow) included, then the linter.
test: $(STAMP)
	$(PY) -m pytest -q -n 2 --dist loadgroup
	$(VENV)/bin/ruff check .

# Everything but the tests marked slow: for quick iterations.
test-fast: $(STAMP)
	$(PY) -m pytest -q -n 2 --dist loadgroup -m "not slow"

lint: $(STAMP)
	$(VENV)/bin/ruff check .

bench: $(STAMP)
	$(PY) benchmarks/run_all.py

clean:
	rm -rf $(VENV) out .pytest_cache .ruff_cache .hypothesis
