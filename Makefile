# Conveniences over the README's two commands (which need nothing but bash).
.PHONY: setup run test bench slow mpi-demo lint

setup:
	bash .ci/setup

run:
	bash .ci/main

test:
	bash .ci/test

bench:
	bash .ci/test -m benchmark -s

slow:
	bash .ci/test -m slow

lint:
	.venv/bin/python -m ruff check fewear tests demos
