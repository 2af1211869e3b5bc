# abrdf - the two commands of the README's quick start, and their parts.
#   make run    install what is missing, build, run the main job on the built-in defaults
#   make test   install what is missing, build, run the whole test suite (normal + ASan/UBSan)
#   make tables rewrite the generated files (tables, the ports' copies, the teapot mesh)
BUILD      ?= build
BUILD_ASAN ?= build-asan
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: all setup setup-ports build build-asan run test tables clean

all: build

# Debian packages to build, run and test the library and the tool.
setup:
	@scripts/setup.sh --no-bpy

# Everything the port tests need as well: POV-Ray and bpy (Cycles + OSL) in .venv.
setup-ports:
	@scripts/setup.sh

build: setup
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

build-asan: setup
	cmake -S . -B $(BUILD_ASAN) -DCMAKE_BUILD_TYPE=Debug -DABRDF_SANITIZE=ON
	cmake --build $(BUILD_ASAN) -j $(JOBS)

run: build
	$(BUILD)/bin/abrdf models
	$(BUILD)/bin/abrdf eval disney_specular --wi 0.3,0,1 --wo -0.2,0.1,1 --set r=0.3
	$(BUILD)/bin/abrdf eval f_2e --wi 0.3,0,1 --wo -0.3,0,1 --set n=300
	$(BUILD)/bin/abrdf render scenes/robot.scene --adaptive --goal photoreal -o $(BUILD)/robot.exr --explain

test: setup-ports build build-asan
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)
	cd $(BUILD_ASAN) && ctest --output-on-failure -j $(JOBS)

# Rewrite every generated file of the tree (README, "Generated files").
tables: build
	python3 tools/gen/gen_tables.py $(BUILD)/bin

clean:
	rm -rf $(BUILD) $(BUILD_ASAN)
