# src/fmu/fmu.mk - `make fmu` (included by the top-level Makefile):
#   build/hexaglide.fmu       the virtual machine as an FMI 3.0 co-simulation FMU
#                             (x86_64-linux binary + sources, docs/fmu.md)
#   build/fmu/fmusim          the FMI standard's own simulator (third_party/reference-fmus),
#                             built against Debian's libxml2, minizip/zlib and SUNDIALS
#   build/fmu/BouncingBall.fmu, build/fmu/Feedthrough.fmu   two Reference FMUs for fmusim
#   build/fmu/tests/*         the C drivers of tests/fmu (and their ASan + UBSan builds)
# The FMU's modelDescription.xml is written by build/fmu/fmu-gen from the
# core's parameter table; fmusim's schema is flattened from the standard's
# .xsd files (third_party/fmi-standard/schema).

FMU_DIR   := $(BUILD)/fmu
FMU_TREE  := $(FMU_DIR)/hexaglide
FMU_PLAT  := x86_64-linux
FMI3_INC  := third_party/fmi-standard/headers
REF       := third_party/reference-fmus
FMU_CFLAGS := $(CFLAGS_PORTABLE) -I$(FMI3_INC) -Isrc/fmu -fPIC   # (an FMU runs on any x86-64: no HOST_ARCH)
# the FMU's own sources (fmu_gen.c is the build-time generator, not in the FMU)
FMU_GLUE  := src/fmu/fmu_fmi3.c src/fmu/fmu_vars.c src/fmu/fmu_plant.c
FMU_HDRS  := $(wildcard src/fmu/*.h)
FMU_OBJS  := $(patsubst src/%.c,$(FMU_DIR)/obj/%.o,$(FMU_GLUE))
FMU_CORE_SRCS := $(filter-out $(THREAD_SRCS),$(CORE_SRCS))   # an FMU starts no threads
FMU_CORE  := $(patsubst src/%.c,$(FMU_DIR)/obj/%.o,$(FMU_CORE_SRCS))

.PHONY: fmu fmu-deps

fmu: fmu-deps $(BUILD)/hexaglide.fmu $(FMU_DIR)/fmusim $(FMU_DIR)/BouncingBall.fmu $(FMU_DIR)/Feedthrough.fmu \
     $(FMU_DIR)/tests/fmu_api $(FMU_DIR)/tests/fmu_fuzz $(FMU_DIR)/tests-asan/fmu_fuzz \
     $(FMU_DIR)/tests-asan/fmu_api

fmu-deps:
	@tools/install-deps.sh fmu

# every object of the FMU and its tools: position independent, the core's flags
$(FMU_DIR)/obj/%.o: src/%.c $(wildcard src/*.h src/generated/*.h) $(FMU_HDRS)
	@mkdir -p $(dir $@)
	$(CC) $(FMU_CFLAGS) -c -o $@ $<

$(FMU_DIR)/fmu-gen: $(FMU_DIR)/obj/fmu/fmu_gen.o $(FMU_DIR)/obj/fmu/fmu_vars.o $(FMU_DIR)/obj/fmu/fmu_plant.o $(FMU_CORE)
	$(CC) -o $@ $^ $(LDLIBS_HOST)

$(FMU_TREE)/modelDescription.xml: $(FMU_DIR)/fmu-gen
	@mkdir -p $(dir $@)
	$(FMU_DIR)/fmu-gen >$@.tmp && mv $@.tmp $@

# only the fmi3* functions are exported (src/fmu/fmu.map)
$(FMU_TREE)/binaries/$(FMU_PLAT)/hexaglide.so: $(FMU_OBJS) $(FMU_CORE) src/fmu/fmu.map
	@mkdir -p $(dir $@)
	$(CC) -shared -Wl,--version-script=src/fmu/fmu.map -Wl,-Bsymbolic -o $@ $(FMU_OBJS) $(FMU_CORE) $(LDLIBS_HOST)

# sources/: everything another platform needs to build the binary but the FMI headers (FMI 3.0 2.5.1: the
# importer supplies them), and its buildDescription.xml
FMU_SRC_FILES := $(FMU_CORE_SRCS) $(FMU_GLUE) $(wildcard src/*.h src/generated/*.h) $(FMU_HDRS)
$(FMU_TREE)/sources/buildDescription.xml: $(FMU_SRC_FILES) src/fmu/fmu.mk
	@rm -rf $(FMU_TREE)/sources && mkdir -p $(FMU_TREE)/sources
	cp $(FMU_SRC_FILES) $(FMU_TREE)/sources/
	{ echo '<?xml version="1.0" encoding="UTF-8"?>'; \
	  echo '<fmiBuildDescription fmiVersion="3.0">'; \
	  echo '  <!-- compilerOptions: round as build/hexaglide does (no FMA, libm sin and cos) -->'; \
	  echo '  <BuildConfiguration modelIdentifier="hexaglide" description="the virtual Hexaglide, C99, libm">'; \
	  echo '    <SourceFileSet language="C99" compiler="gcc" compilerOptions="-std=c99 $(RT_SAME_FLAGS)">'; \
	  for f in $(notdir $(FMU_CORE_SRCS) $(FMU_GLUE)); do echo "      <SourceFile name=\"$$f\"/>"; done; \
	  echo '    </SourceFileSet>'; \
	  echo '    <Library name="m"/>'; \
	  echo '  </BuildConfiguration>'; \
	  echo '</fmiBuildDescription>'; } >$@

$(BUILD)/hexaglide.fmu: $(FMU_TREE)/modelDescription.xml $(FMU_TREE)/binaries/$(FMU_PLAT)/hexaglide.so \
                        $(FMU_TREE)/sources/buildDescription.xml
	rm -f $@ && cd $(FMU_TREE) && zip -qrX $(CURDIR)/$@ modelDescription.xml binaries sources

# ---- fmusim (third_party/reference-fmus/fmusim), Debian's libraries ----
FMUSIM_SRCS := $(wildcard $(REF)/fmusim/*.c) $(REF)/src/FMI.c $(REF)/src/FMI1.c $(REF)/src/FMI2.c $(REF)/src/FMI3.c \
               $(REF)/src/structured_variable_name.tab.c $(REF)/src/structured_variable_name.yy.c
FMUSIM_CFLAGS := -std=gnu99 -O2 -g '-DFMUSIM_VERSION="0.0.39-c8d4e6d"' -I$(FMU_DIR)/schema -I$(REF)/fmusim \
                 -I$(REF)/include -I$(FMI3_INC) $(shell pkg-config --cflags libxml-2.0 minizip 2>/dev/null)
FMUSIM_LIBS := -lxml2 -lminizip -lz -lsundials_cvode -lsundials_nvecserial -ldl -lm

# the schema fmusim validates against: the standard's .xsd files flattened by Reference-FMUs' own script
$(FMU_DIR)/schema/fmi3schema.h: $(wildcard third_party/fmi-standard/schema/*.xsd) $(REF)/build/xsdflatten.py
	@mkdir -p $(dir $@)
	cd third_party/fmi-standard/schema && PYTHONHASHSEED=0 /usr/bin/python3 $(CURDIR)/$(REF)/build/xsdflatten.py \
	    fmi3ModelDescription.xsd >$(CURDIR)/$(FMU_DIR)/schema/fmi3Merged.xsd
	cd $(FMU_DIR)/schema && xxd -i fmi3Merged.xsd >fmi3schema.h.tmp && mv fmi3schema.h.tmp fmi3schema.h

$(FMU_DIR)/fmusim: $(FMUSIM_SRCS) $(wildcard $(REF)/fmusim/*.h $(REF)/include/*.h) $(FMU_DIR)/schema/fmi3schema.h
	$(CC) $(FMUSIM_CFLAGS) -w -o $@ $(FMUSIM_SRCS) $(FMUSIM_LIBS)

# ---- the Reference FMUs BouncingBall and Feedthrough, built from the copied sources ----
$(FMU_DIR)/%.fmu: $(REF)/%/model.c $(REF)/%/config.h $(REF)/%/FMI3.xml $(REF)/src/fmi3Functions.c $(REF)/src/cosimulation.c
	@rm -rf $(FMU_DIR)/ref/$* && mkdir -p $(FMU_DIR)/ref/$*/binaries/$(FMU_PLAT)
	$(CC) -std=gnu99 -O2 -shared -fPIC -fvisibility=hidden -DFMI_VERSION=3 -DDISABLE_PREFIX -I$(REF)/$* \
	    -I$(REF)/include -I$(FMI3_INC) -o $(FMU_DIR)/ref/$*/binaries/$(FMU_PLAT)/$*.so $(REF)/$*/model.c \
	    $(REF)/src/fmi3Functions.c $(REF)/src/cosimulation.c -lm
	cp $(REF)/$*/FMI3.xml $(FMU_DIR)/ref/$*/modelDescription.xml
	rm -f $@ && cd $(FMU_DIR)/ref/$* && zip -qrX $(CURDIR)/$@ modelDescription.xml binaries

# ---- C drivers of tests/fmu, on the FMI API (linked with the FMU's objects) ----
$(FMU_DIR)/tests/%: tests/fmu/%.c tests/fmu/fmu_test.h $(FMU_OBJS) $(FMU_CORE)
	@mkdir -p $(dir $@)
	$(CC) $(FMU_CFLAGS) -Itests/fmu -o $@ $< $(FMU_OBJS) $(FMU_CORE) $(LDLIBS_HOST)

# ... and under ASan + UBSan (the FMU's and the core's sources compiled again, into asan-obj)
FMU_ASAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FMU_ASAN_OBJS := $(patsubst src/%.c,$(FMU_DIR)/asan-obj/%.o,$(FMU_GLUE) $(FMU_CORE_SRCS))
$(FMU_DIR)/asan-obj/%.o: src/%.c $(wildcard src/*.h src/generated/*.h) $(FMU_HDRS)
	@mkdir -p $(dir $@)
	$(CC) $(FMU_CFLAGS) $(FMU_ASAN) -c -o $@ $<
$(FMU_DIR)/tests-asan/%: tests/fmu/%.c tests/fmu/fmu_test.h $(FMU_ASAN_OBJS)
	@mkdir -p $(dir $@)
	$(CC) $(FMU_CFLAGS) $(FMU_ASAN) -Itests/fmu -o $@ $< $(FMU_ASAN_OBJS) $(LDLIBS_HOST) $(FMU_ASAN)
