# The front door (`make help` lists every target): `make book` builds the book, `make test` runs the graph of
# `python -m mechlib.pipeline test` (docs/testing.md). All runs in .venv, from environment.lock (Python 3.11.7).
SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := help
PYTHON_BOOT ?= python3
PY       := .venv/bin/python
UV       := .venv/bin/uv
STAMP    := .venv/.lock-stamp
PIPELINE := $(PY) -m mechlib.pipeline
# PROFILE: ci (the notebooks' defaults: tests/references) or notebooks/profiles/<name>/ (docs/rerunning.md)
PROFILE     ?= ci
BUILD       := build$(if $(filter-out ci,$(PROFILE)),/$(PROFILE))
PROFILE_DIR := notebooks/profiles/$(PROFILE)
include build/chapters.mk  # the chapters (NB_NAMES) and the order of their inputs: mechlib/pipeline/chapters.py
build/chapters.mk: mechlib/pipeline/chapters.py
	@mkdir -p build && $(PYTHON_BOOT) $< makefile > $@
EXECUTED := $(patsubst %,$(BUILD)/executed/%.ipynb,$(NB_NAMES))
# the science wing (mechlib minus the build wing): a change there re-executes the notebooks
MECHLIB_SRC := $(filter-out mechlib/pipeline/%,$(shell find mechlib -name '*.py' 2>/dev/null))
FE_CACHE     := build/cache/experiments
STORE_SEEDED := $(FE_CACHE)/.store-seeded
REQUIRE_CI    = @test "$(PROFILE)" = ci || { echo "make $@ runs the ci profile only; got PROFILE=$(PROFILE)"; exit 2; }
BOOK_JOBS ?= $(shell n=$$(nproc 2>/dev/null || echo 1); echo $$(( n < 4 ? n : 4 )))
export PYTHONHASHSEED := 0
export PYDEVD_DISABLE_FILE_VALIDATION := 1
# bytecode cached in .venv: else every kernel compiles the FE stack again (7.0 s against 2.9 s to import it)
unexport PYTHONDONTWRITEBYTECODE
.PHONY: help env lock book notebooks test unit check-records check-book check-browser pdf check-pdf rerun run references bench lint clean store store-seed store-check
help:
	@echo "make book           the HTML book (creates .venv, executes what changed; BOOK_JOBS=1: one at a time; PROFILE=full)"
	@echo "make test           what CI checks, a graph of steps (docs/testing.md); ONLY=step,...: some of them"
	@echo "make unit           the unit tests (make test ONLY=unit-a,unit-b); make lint: ruff check and format"
	@echo "make notebooks      execute the notebooks that changed (-j2: two at once); make check-records: their records"
	@echo "make check-book     the built HTML; make check-browser: every page in headless Chromium, offline"
	@echo "make pdf            print the built book to book/_build/pdf/book.pdf; make check-pdf: check it"
	@echo "make rerun          every notebook again, cold, into build/rerun (FE_CACHE_FROM=, FIRST_RUN=: docs/determinism.md)"
	@echo "make run NB=name ARGS='-p key value ...'   one notebook with new parameters; make references: re-record tests/references"
	@echo "make bench          speed benchmarks; ONLY=nonlinear,chapter: some; ONLY=book: make book on a fresh clone"
	@echo "make store          regenerate the FE results store (FROM_EMPTY=1, DASK_SCHEDULER=tcp://host:port)"
	@echo "make store-seed     seed build/cache from store/ again; make store-check: its cold sample"
	@echo "make env            create .venv from environment.lock; make lock: regenerate the lock"
	@echo "make clean          remove $(BUILD) and the generated book"
env: $(STAMP)
$(UV): .ci/bootstrap.lock
	test -x $(PY) || $(PYTHON_BOOT) -m venv .venv
	$(PY) -m pip install -q --disable-pip-version-check --require-hashes -r .ci/bootstrap.lock
	touch $@
$(STAMP): environment.lock $(UV) pyproject.toml
	$(UV) pip sync -q --python $(PY) environment.lock
	$(UV) pip install -q --python $(PY) --no-deps --no-build-isolation -e .
	touch $@
lock: $(UV)
	$(UV) pip compile requirements.in --generate-hashes --python-version 3.11.7 -o environment.lock
# an executed notebook depends on its source, the science wing and the environment only (into .tmp.ipynb first)
$(BUILD)/executed/%.ipynb: notebooks/%.ipynb $(MECHLIB_SRC) $(STAMP) $(wildcard $(PROFILE_DIR)/*.yaml) | $(STORE_SEEDED)
	@test "$(PROFILE)" = ci || test -d $(PROFILE_DIR) || { echo "no profile $(PROFILE_DIR)"; exit 2; }; echo "executing $< (profile $(PROFILE))"
	@mkdir -p $(BUILD)/executed $(BUILD)/records
	$(PIPELINE) execute --notebook $< --out $(BUILD)/executed/$*.tmp.ipynb --records $(BUILD)/records \
	  -- $(if $(wildcard $(PROFILE_DIR)/$*.yaml),-f $(PROFILE_DIR)/$*.yaml)
	mv $(BUILD)/executed/$*.tmp.ipynb $@
notebooks: $(EXECUTED)
# the HTML is rebuilt from scratch (seconds): an incremental Sphinx build re-reports no warning
book: $(STAMP)
	$(MAKE) --no-print-directory -j$(BOOK_JOBS) notebooks
	$(PIPELINE) book --executed $(BUILD)/executed --records $(BUILD)/records --book book --profile $(PROFILE)
	rm -rf book/_build && .venv/bin/jupyter-book build book -W -n --keep-going --quiet
	@echo "Book: $(abspath book/_build/html/index.html)"
test: $(STAMP)
	$(REQUIRE_CI)
	$(PIPELINE) test $(if $(ONLY),--only $(ONLY))
unit: $(STAMP)
	$(PIPELINE) test --only unit-a,unit-b
lint: $(STAMP)
	.venv/bin/ruff check mechlib tests notebooks && .venv/bin/ruff format --check mechlib tests notebooks
check-records: $(EXECUTED)
	.venv/bin/pytest -q tests/test_records.py
check-book: $(STAMP)
	MECHLIB_REQUIRE_BOOK=1 .venv/bin/pytest -q tests/test_book_html.py tests/test_explorer_browser.py
check-browser: $(STAMP)
	$(PIPELINE) check-browser --html book/_build/html --book book
# the single-page HTML printed by headless Chromium after MathJax ran (docs/pdf.md)
pdf: $(STAMP)
	@test -f book/_build/html/index.html || { echo "no HTML book: run make book first"; exit 2; }; rm -rf book/_build/singlehtml
	.venv/bin/jupyter-book build book --builder singlehtml -W -n --keep-going --quiet && $(PY) -m mechlib.pipeline.pdf build --html book/_build/singlehtml --out book/_build/pdf/book.pdf
check-pdf: $(STAMP)
	$(PY) -m mechlib.pipeline.pdf check --pdf book/_build/pdf/book.pdf --html book/_build/singlehtml --min-pages $(or $(PDF_MIN_PAGES),50) --max-pages $(or $(PDF_MAX_PAGES),130)
rerun: $(STAMP)
	$(REQUIRE_CI)
	$(PIPELINE) rerun --out $(abspath $(BUILD)/rerun) $(if $(FE_CACHE_FROM),--fe-cache-from $(FE_CACHE_FROM)) $(if $(FIRST_RUN),--first-run $(FIRST_RUN))
run: $(STAMP) $(STORE_SEEDED)
	@test -n "$(NB)" || { echo "usage: make run NB=<notebook name> ARGS='-p name value ...'"; exit 2; }; test -f notebooks/$(NB).ipynb || { echo "no notebook notebooks/$(NB).ipynb; have: $(NB_NAMES)"; exit 2; }
	$(PIPELINE) run --notebook notebooks/$(NB).ipynb --out $(BUILD)/runs --records $(BUILD)/records -- $(ARGS)
references: $(EXECUTED)
	$(REQUIRE_CI)
	$(PIPELINE) update --records $(BUILD)/records --references tests/references
comma := ,
BENCH_ON_MODEL := $(if $(ONLY),$(filter nonlinear chapter reuse rom dask,$(subst $(comma), ,$(ONLY))),all)
bench: $(STAMP) $(if $(BENCH_ON_MODEL),$(BUILD)/executed/hexflex_model.ipynb)
	MECHLIB_RECORDS=$(abspath $(BUILD)/records) $(PY) -m mechlib.bench $(if $(ONLY),--only $(ONLY))
clean:
	rm -rf $(BUILD) book/_build book/chapters book/generated book/report.md book/report_beyond.md book/intro.md
# the FE results store: a stale, edited or corrupt store is refused in one line before any notebook runs
$(STORE_SEEDED): $(wildcard store/manifest.json store/results.npz store/snapshots.npz) | $(STAMP)
	$(if $(NO_STORE_SEED),@echo "store: not read (make store FROM_EMPTY=1 solves every FE task)",\
	  $(PIPELINE) store seed --store store --cache $(FE_CACHE) && touch $@)
store-seed: $(STAMP)
	$(PIPELINE) store seed --store store --cache $(FE_CACHE) && mkdir -p $(FE_CACHE) && touch $(STORE_SEEDED)
store-check: $(STAMP)
	@if test -f store/manifest.json; then $(PIPELINE) store check --store store; else echo "store-check skipped: no store/manifest.json (make store)"; fi
store: $(STAMP)
	$(REQUIRE_CI)
	$(PIPELINE) store clean $(if $(FROM_EMPTY)$(NO_STORE_SEED),,--reads-store) && rm -rf $(BUILD)/executed $(BUILD)/store-tasks.jsonl $(if $(FROM_EMPTY),$(FE_CACHE)) && mkdir -p $(BUILD)
	start=$$(date +%s); head=$$(git rev-parse --short=12 HEAD); \
	MECHLIB_FE_LOG=$(abspath $(BUILD)/store-tasks.jsonl) $(if $(DASK_SCHEDULER),MECHLIB_DASK_SCHEDULER=$(DASK_SCHEDULER)) \
	  $(MAKE) --no-print-directory -j2 notebooks $(if $(FROM_EMPTY),NO_STORE_SEED=1) && \
	$(PIPELINE) store pack --log $(BUILD)/store-tasks.jsonl --cache $(FE_CACHE) --store store --commit $$head \
	  --seconds $$(( $$(date +%s) - start )) $(if $(FROM_EMPTY),--from-empty) $(if $(FROM_EMPTY),$(if $(wildcard store/manifest.json),--compare store)) \
	  --workers "$(if $(DASK_SCHEDULER),Dask cluster $(DASK_SCHEDULER),the notebooks' local worker processes)"
