# fegear: two commands for a fresh machine with Python 3.11 and pip.
#   make demo   set up .venv and run the main job
#   make test   set up .venv, lint, run the default test suite
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed-stamp

.PHONY: demo test test-all lint bench study clean system-programs

# PYTHONWARNINGS=ignore: setuptools' boxed notice on every editable install is no news to a user
$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	PYTHONWARNINGS=ignore $(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/fegear solve --out out/demo  # the seed paper's pair (the defaults), 200 N·m

lint: $(STAMP)
	$(BIN)/ruff check fegear tests

test: system-programs lint
	$(BIN)/python -m pytest -q -n 2  # two workers: the CI machine's two cores

test-all: system-programs lint
	$(BIN)/python -m pytest -q -n 2 -m "" --ignore=tests/verify/sector
	# the sector peer's files take 3-14 GB each (12.6 GB for test_stability, 13.7 for
	# test_solve): one at a time, each in a process of its own, so two never share 24 GB
	for f in tests/verify/sector/test_*.py; do $(BIN)/python -m pytest -q -m "" $$f || exit 1; done

# the programs some tests need (CalculiX, Chromium), where they are missing and the tests can
# install them (root, apt-get), installed in the background from here on: a first run's install
# overlaps building .venv and the tests (tests/system.py)
system-programs:
	@$(PYTHON) tests/system.py start ccx chromium

bench: $(STAMP)
	# the paper's baseline pair; the sector model and CalculiX beside it, the paper study, a
	# tolerance class's samples, a load spectrum, whole revolutions and the design search over a
	# turn timed
	$(BIN)/fegear bench --shift 0.016 --rotation 0.002 --sector-levels coarse,fast --paper-study \
		--tolerance-class --spectrum --revolution --search --history docs/bench/history.jsonl

study: $(STAMP)
	$(BIN)/fegear study studies/paper_trends.toml  # the paper's Tables 4-6, about 15 s

clean:
	rm -rf $(VENV) out .pytest_cache
