# The figure pipeline: data by the coatcontact CLI, plots by the gnuplot scripts next to
# this file. Included by the top-level Makefile (`make figures`); also usable on its own
# with an already-built CLI, e.g. (this is what tests/figures does):
#
#   make -f gnuplot/figures.mk figures-only CLI=build/bin/coatcontact \
#        FIGURES_CONF=tests/figures/figures-test.conf DATA_DIR=/tmp/d FIG_DIR=/tmp/f
#
# Incremental: every dataset and figure has a parameter stamp $(DATA_DIR)/params/<name>.params
# holding its exact command line. The stamps are rewritten on every run but only replaced
# (new mtime) when their content changes, so a changed parameter in $(FIGURES_CONF) rebuilds
# just the datasets and figures that use it, and a second run rebuilds nothing.
# Atomic writes: the CLI's --output is atomic; gnuplot writes $(FIG_DIR)/.partial/<file>, then
# mv renames it into $(FIG_DIR).

GNUPLOT_DIR := $(patsubst %/,%,$(dir $(lastword $(MAKEFILE_LIST))))

BUILD        ?= build
JOBS         ?= 2
CLI          ?= $(BUILD)/bin/coatcontact
GNUPLOT      ?= gnuplot
FIGURES_CONF ?= data/figures.conf
DATA_DIR     ?= $(BUILD)/data
FIG_DIR      ?= $(BUILD)/figures
PARAMS_DIR   := $(DATA_DIR)/params
# gnuplot writes into PLOT_TMP; one mv then renames a group of plots into FIG_DIR.
PLOT_TMP     := $(FIG_DIR)/.partial
# Solve cache of the CLI (docs/solver.md): none unless given; `make figures` uses $(BUILD)/cache.
SOLVE_CACHE  ?=

include $(FIGURES_CONF)

comma := ,
empty :=
space := $(empty) $(empty)

# ---- datasets: name -> CLI arguments (CMD_<name>) ------------------------------------
# Substrate E0 = 1, film E1 = ratio (see data/figures.conf).
materials = --film $(1),$(NU_FILM) --substrate 1,$(NU_SUBSTRATE)

REDUCED_RATIOS  := $(sort $(SOFT_RATIO) $(STIFF_RATIO) $(FIT_RATIOS))
ADHESIVE_RATIOS := $(sort $(SOFT_RATIO) $(STIFF_RATIO))

$(foreach r,$(REDUCED_RATIOS),$(eval \
  CMD_reduced_E$(r) := reduced $(call materials,$(r)) --a-over-t $(REDUCED_A_OVER_T)))
$(foreach r,$(ADHESIVE_RATIOS),$(eval \
  CMD_adhesive_E$(r) := adhesive $(call materials,$(r)) --eta $(ETA) --a-bar $(A_BAR)))
$(foreach r,$(PULLOFF_RATIOS),$(eval \
  CMD_pulloff_E$(r) := pulloff $(call materials,$(r)) --eta $(PULLOFF_ETA)))
# pull-off points on the curves of figs 5-7: the same eta set as the curves
$(foreach r,$(ADHESIVE_RATIOS),$(eval \
  CMD_pulloffeta_E$(r) := pulloff $(call materials,$(r)) --eta $(ETA)))
CMD_fig2_curve  := reduced $(call materials,$(FIG2_RATIO)) --a-over-t $(FIG2_CURVE_A_OVER_T)
CMD_fig2_points := reduced $(call materials,$(FIG2_RATIO)) \
  --a-over-t $(FIG2_A_OVER_T),$(FIG2_A_OVER_T_NEXT)

# Figures 10-12 (THEORY.md sections 9-11): spring, elastic indenter, shapes.
$(foreach r,$(SPRING_RATIOS),$(eval \
  CMD_spring_E$(r) := pulloff $(call materials,$(r)) --eta $(SPRING_ETA) --spring-bar $(SPRING_K_BAR)))
# E2 = ratio x E1 with the film's Poisson ratio, so E2*/E1* = ratio.
INDENTER_NAMES := $(INDENTER_RATIOS) rigid
indenter_arg = $(if $(filter rigid,$(1)),rigid,$(shell awk 'BEGIN { print $(1) * $(INDENTER_FILM_RATIO) }'),$(NU_FILM))
$(foreach i,$(INDENTER_NAMES),$(eval \
  CMD_indenter_I$(i) := pulloff $(call materials,$(INDENTER_FILM_RATIO)) --indenter $(call indenter_arg,$(i)) \
    --eta $(INDENTER_ETA)))
shape_name = $(firstword $(subst :, ,$(1)))
$(foreach s,$(SHAPE_LIST),$(eval \
  CMD_shape_$(call shape_name,$(s)) := contact --shape $(s) --thickness $(SHAPE_THICKNESS) --film $(SHAPE_FILM) \
    --substrate $(SHAPE_SUBSTRATE) --work $(SHAPE_WORK) --points $(SHAPE_POINTS)))
# Maugis-Dugdale pull-off versus lambda (THEORY.md section 13): the two films and the
# homogeneous solid (eta is irrelevant there), with the JKR pull-offs (lambda = inf).
$(foreach r,$(ADHESIVE_RATIOS),$(eval \
  CMD_mdlambda_E$(r) := pulloff $(call materials,$(r)) --eta $(MD_ETA) --lambda $(MD_LAMBDA)))
$(foreach r,$(ADHESIVE_RATIOS),$(eval \
  CMD_mdjkr_E$(r) := pulloff $(call materials,$(r)) --eta $(MD_ETA)))
CMD_mdlambda_homogeneous := pulloff $(call materials,1) --eta 1 --lambda $(MD_LAMBDA)
CMD_mdcurves := adhesive $(call materials,$(SOFT_RATIO)) --eta $(MD_CURVE_ETA) \
  --lambda $(subst $(space),$(comma),$(MD_CURVE_LAMBDAS)) --a-bar $(MD_CURVE_A_BAR)
CMD_mdcurves_jkr := adhesive $(call materials,$(SOFT_RATIO)) --eta $(MD_CURVE_ETA) --a-bar $(MD_CURVE_A_BAR)

# Stacks of layers (THEORY.md section 12): a three-layer stack against its one-layer
# approximations (the top layer alone; thickness-weighted E and nu), and one film bonded
# versus sliding on its substrate. Every curve is normalized by its own top layer's E*.
stack_layers := $(foreach l,$(STACK_LAYERS),--layer $(l))
STACK_TOP := $(shell echo '$(firstword $(STACK_LAYERS))' | awk -F, '{ print $$2 "," $$3 }')
STACK_AVG := $(shell echo '$(STACK_LAYERS)' | awk '{ for (i = 1; i <= NF; i++) { split($$i, a, ","); \
  h += a[1]; e += a[1] * a[2]; n += a[1] * a[3] } printf "%.10g,%.10g", e / h, n / h }')
# E*_avg / E*_top: rescales the average model's E_eq and eta to the top layer's units.
STACK_AVG_SCALE := $(shell echo '$(STACK_TOP) $(STACK_AVG)' | awk '{ split($$1, t, ","); split($$2, a, ","); \
  printf "%.10g", a[1] / (1 - a[2] ^ 2) / (t[1] / (1 - t[2] ^ 2)) }')
STACK_MODELS := stack top avg
stack_materials = $(if $(filter stack,$(1)),$(stack_layers),--film $(if $(filter top,$(1)),$(STACK_TOP),$(STACK_AVG))) \
  --substrate $(STACK_SUBSTRATE)
$(foreach m,$(STACK_MODELS),$(eval \
  CMD_stackreduced_$(m) := reduced $(call stack_materials,$(m)) --a-over-t $(STACK_A_OVER_T)))
$(foreach m,$(STACK_MODELS),$(eval \
  CMD_stackpulloff_$(m) := pulloff $(call stack_materials,$(m)) --eta $(STACK_ETA)))
SLIP_MODELS := bonded sliding
slip_materials = --layer 1,$(SLIP_FILM)$(if $(filter sliding,$(1)),$(comma)slip) --substrate $(SLIP_SUBSTRATE)
$(foreach m,$(SLIP_MODELS),$(eval \
  CMD_slipreduced_$(m) := reduced $(call slip_materials,$(m)) --a-over-t $(STACK_A_OVER_T)))
$(foreach m,$(SLIP_MODELS),$(eval \
  CMD_slippulloff_$(m) := pulloff $(call slip_materials,$(m)) --eta $(STACK_ETA)))

data = $(DATA_DIR)/$(1).tsv
PULLOFF_FILES := $(foreach r,$(PULLOFF_RATIOS),$(call data,pulloff_E$(r)))

# ---- figures: name -> gnuplot variables (GP_<name>) and datasets (DATA_<name>) ---------
# The variables are passed with `gnuplot -e`; strings in single quotes.
GP_common = gpdir='$(GNUPLOT_DIR)'; nu1=$(NU_FILM); nu0=$(NU_SUBSTRATE)

DATA_fig1 :=
GP_fig1    = $(GP_common)
DATA_fig2  = $(call data,fig2_curve) $(call data,fig2_points)
GP_fig2    = $(GP_common); ratio=$(FIG2_RATIO); eta=$(FIG2_ETA); \
             curve='$(call data,fig2_curve)'; points='$(call data,fig2_points)'
DATA_fig3  = $(call data,reduced_E$(SOFT_RATIO))
GP_fig3    = $(GP_common); ratio=$(SOFT_RATIO); reduced='$(DATA_fig3)'
DATA_fig4  = $(call data,reduced_E$(STIFF_RATIO))
GP_fig4    = $(GP_common); ratio=$(STIFF_RATIO); reduced='$(DATA_fig4)'
DATA_fig5  = $(call data,adhesive_E$(SOFT_RATIO)) $(call data,pulloffeta_E$(SOFT_RATIO))
GP_fig5    = $(GP_common); ratio=$(SOFT_RATIO); adhesive='$(call data,adhesive_E$(SOFT_RATIO))'; \
             pulloff='$(call data,pulloffeta_E$(SOFT_RATIO))'
DATA_fig6  = $(call data,adhesive_E$(SOFT_RATIO)) $(call data,pulloffeta_E$(SOFT_RATIO))
GP_fig6    = $(GP_common); ratio=$(SOFT_RATIO); adhesive='$(call data,adhesive_E$(SOFT_RATIO))'; \
             pulloff='$(call data,pulloffeta_E$(SOFT_RATIO))'
DATA_fig7  = $(call data,adhesive_E$(STIFF_RATIO)) $(call data,pulloffeta_E$(STIFF_RATIO))
GP_fig7    = $(GP_common); ratio=$(STIFF_RATIO); adhesive='$(call data,adhesive_E$(STIFF_RATIO))'; \
             pulloff='$(call data,pulloffeta_E$(STIFF_RATIO))'
DATA_fig8  = $(PULLOFF_FILES)
GP_fig8    = $(GP_common); ratios='$(PULLOFF_RATIOS)'; files='$(PULLOFF_FILES)'
DATA_fig9  = $(foreach r,$(FIT_RATIOS),$(call data,reduced_E$(r)))
GP_fig9    = $(GP_common); ratios='$(FIT_RATIOS)'; files='$(DATA_fig9)'
DATA_fig_md_lambda = $(foreach r,$(SOFT_RATIO) $(STIFF_RATIO),$(call data,mdlambda_E$(r)) $(call data,mdjkr_E$(r))) \
                     $(call data,mdlambda_homogeneous)
GP_fig_md_lambda   = $(GP_common); ratios='$(SOFT_RATIO) $(STIFF_RATIO)'; etas='$(subst $(comma), ,$(MD_ETA))'; \
                     md='$(foreach r,$(SOFT_RATIO) $(STIFF_RATIO),$(call data,mdlambda_E$(r)))'; \
                     jkr='$(foreach r,$(SOFT_RATIO) $(STIFF_RATIO),$(call data,mdjkr_E$(r)))'; \
                     homogeneous='$(call data,mdlambda_homogeneous)'

SPRING_FILES   := $(foreach r,$(SPRING_RATIOS),$(call data,spring_E$(r)))
DATA_fig10 = $(SPRING_FILES)
GP_fig10   = $(GP_common); ratios='$(SPRING_RATIOS)'; files='$(SPRING_FILES)'; eta=$(SPRING_ETA)
INDENTER_FILES := $(foreach i,$(INDENTER_NAMES),$(call data,indenter_I$(i)))
DATA_fig11 = $(INDENTER_FILES)
GP_fig11   = $(GP_common); ratio=$(INDENTER_FILM_RATIO); indenters='$(INDENTER_NAMES)'; files='$(INDENTER_FILES)'
SHAPE_FILES := $(foreach s,$(SHAPE_LIST),$(call data,shape_$(call shape_name,$(s))))
DATA_fig12 = $(SHAPE_FILES)
GP_fig12   = $(GP_common); shapes='$(SHAPE_LIST)'; files='$(SHAPE_FILES)'

DATA_fig13 = $(call data,mdcurves) $(call data,mdcurves_jkr)
GP_fig13   = $(GP_common); ratio=$(SOFT_RATIO); eta=$(MD_CURVE_ETA); lambdas='$(MD_CURVE_LAMBDAS)'; \
             md='$(call data,mdcurves)'; jkr='$(call data,mdcurves_jkr)'

DATA_fig_stack = $(foreach m,$(STACK_MODELS),$(call data,stackreduced_$(m)) $(call data,stackpulloff_$(m))) \
                 $(foreach m,$(SLIP_MODELS),$(call data,slipreduced_$(m)) $(call data,slippulloff_$(m)))
GP_fig_stack   = $(GP_common); layers='$(STACK_LAYERS)'; base='$(STACK_SUBSTRATE)'; \
                 film='$(SLIP_FILM)'; film_base='$(SLIP_SUBSTRATE)'; avg='$(STACK_AVG)'; avg_scale=$(STACK_AVG_SCALE); \
                 reduced='$(foreach m,$(STACK_MODELS),$(call data,stackreduced_$(m)))'; \
                 pulloff='$(foreach m,$(STACK_MODELS),$(call data,stackpulloff_$(m)))'; \
                 slip_reduced='$(foreach m,$(SLIP_MODELS),$(call data,slipreduced_$(m)))'; \
                 slip_pulloff='$(foreach m,$(SLIP_MODELS),$(call data,slippulloff_$(m)))'

# Rate-dependent adhesion (THEORY.md section 14): pull-off against the retract rate on the soft
# and stiff films and the homogeneous solid, and P(D) loops on the soft film at three rates.
# Reduced units; defaults here so that a conf file without them still works.
KIN_ETA      ?= 1
KIN_N        ?= 0.6
KIN_K_BAR    ?= 1
KIN_PROTOCOL ?= approach:1:1,dwell:1
KIN_SPEEDS   ?= 1e-4:1e4:25
KIN_LOOPS    ?= 0.01 1 100
KIN_RATIOS   := $(SOFT_RATIO) $(STIFF_RATIO) 1
kin_args = kinetics $(call materials,$(1)) --eta $(KIN_ETA) --n $(KIN_N) --k-bar $(KIN_K_BAR)
$(foreach r,$(KIN_RATIOS),$(eval \
  CMD_kinsweep_E$(r) := $(call kin_args,$(r)) --protocol $(KIN_PROTOCOL),retract:1 --retract-speeds $(KIN_SPEEDS)))
$(foreach v,$(KIN_LOOPS),$(eval \
  CMD_kinloop_V$(v) := $(call kin_args,$(SOFT_RATIO)) --protocol $(KIN_PROTOCOL),retract:$(v)))
DATA_fig_kinetics = $(foreach r,$(KIN_RATIOS),$(call data,kinsweep_E$(r))) \
                    $(foreach v,$(KIN_LOOPS),$(call data,kinloop_V$(v)))
GP_fig_kinetics   = $(GP_common); ratios='$(KIN_RATIOS)'; speeds='$(KIN_LOOPS)'; n=$(KIN_N); \
                    k_bar=$(KIN_K_BAR); eta=$(KIN_ETA); \
                    sweeps='$(foreach r,$(KIN_RATIOS),$(call data,kinsweep_E$(r)))'; \
                    loops='$(foreach v,$(KIN_LOOPS),$(call data,kinloop_V$(v)))'

FIGURE_NAMES := fig1 fig2 fig3 fig4 fig5 fig6 fig7 fig8 fig9 fig10 fig11 fig12 fig13 fig_md_lambda fig_stack \
                fig_kinetics
FIGURE_FILES := $(foreach f,$(FIGURE_NAMES),$(FIG_DIR)/$(f).png $(FIG_DIR)/$(f).pdf)

# Helper scripts loaded by the figure scripts.
SCRIPTS_fig3 := $(GNUPLOT_DIR)/reduced_panels.gp
SCRIPTS_fig4 := $(GNUPLOT_DIR)/reduced_panels.gp
SCRIPTS_fig5 := $(GNUPLOT_DIR)/adhesive_data.gp $(GNUPLOT_DIR)/adhesive_curves.gp
SCRIPTS_fig6 := $(GNUPLOT_DIR)/adhesive_data.gp
SCRIPTS_fig7 := $(GNUPLOT_DIR)/adhesive_data.gp $(GNUPLOT_DIR)/adhesive_curves.gp
SCRIPTS_fig9 := $(GNUPLOT_DIR)/eeq_models.gp

$(foreach f,$(FIGURE_NAMES),$(eval \
  $(FIG_DIR)/$(f).png $(FIG_DIR)/$(f).pdf: $(DATA_$(f)) $(SCRIPTS_$(f))))

# Every dataset by name.
DATASET_NAMES := $(foreach r,$(REDUCED_RATIOS),reduced_E$(r)) fig2_curve fig2_points \
  $(foreach r,$(ADHESIVE_RATIOS),adhesive_E$(r) pulloffeta_E$(r)) \
  $(foreach r,$(PULLOFF_RATIOS),pulloff_E$(r)) \
  $(foreach r,$(SPRING_RATIOS),spring_E$(r)) $(foreach i,$(INDENTER_NAMES),indenter_I$(i)) \
  $(foreach s,$(SHAPE_LIST),shape_$(call shape_name,$(s))) \
  $(foreach r,$(ADHESIVE_RATIOS),mdlambda_E$(r) mdjkr_E$(r)) mdlambda_homogeneous \
  mdcurves mdcurves_jkr \
  $(foreach m,$(STACK_MODELS),stackreduced_$(m) stackpulloff_$(m)) \
  $(foreach m,$(SLIP_MODELS),slipreduced_$(m) slippulloff_$(m)) \
  $(foreach r,$(KIN_RATIOS),kinsweep_E$(r)) $(foreach v,$(KIN_LOOPS),kinloop_V$(v))

# The solver tolerance (FIGURE_TOL, data/figures.conf) on every dataset that takes it: the
# Maugis-Dugdale ones (--lambda) refuse --tol. Part of CMD_<name>, so of its parameter stamp.
FIGURE_TOL ?=
$(foreach n,$(DATASET_NAMES),$(if $(FIGURE_TOL),$(if $(findstring --lambda,$(CMD_$(n))),,$(eval \
  CMD_$(n) += --tol $(FIGURE_TOL)))))

# ---- targets -------------------------------------------------------------------------
.PHONY: figures figures-only figures-data figures-docs FORCE

# `make figures`: build the CLI (top-level Makefile's `build-cli`), then the figures with
# $(JOBS) parallel jobs unless the caller already passed -j.
figures: build-cli
	@$(MAKE) --no-print-directory $(if $(filter -j%,$(MAKEFLAGS)),,-j$(JOBS)) figures-only \
	  SOLVE_CACHE='$(if $(SOLVE_CACHE),$(SOLVE_CACHE),$(BUILD)/cache)'

# The slowest datasets first (measured, docs/solver.md "Solve cache"), so that with -j the
# short ones fill the other slots instead of one long run finishing alone at the end. The two
# three-layer stack datasets need the same kernel table (~0.17 s): pulloff_E100 between them
# lets the first store it in the solve cache before the second starts (which would otherwise
# wait for it with its slot idle, docs/speed.md "make figures, second round").
SLOW_DATASETS := $(foreach n,$(filter $(DATASET_NAMES),mdlambda_E$(SOFT_RATIO) mdlambda_E$(STIFF_RATIO) \
  stackpulloff_stack pulloff_E$(lastword $(PULLOFF_RATIOS)) stackreduced_stack mdlambda_homogeneous),$(call data,$(n)))
figures-only: $(SLOW_DATASETS) $(FIGURE_FILES)
	$(plot_queued)
	@echo "figures: $(FIG_DIR)/fig{1..13}.png, fig_md_lambda.png, fig_stack.png, fig_kinetics.png and .pdf   data: $(DATA_DIR)/*.tsv"
	@awk -v etas='$(PULLOFF_TABLE_ETA)' -f $(GNUPLOT_DIR)/pulloff_table.awk $(PULLOFF_FILES)

figures-data: $(PULLOFF_FILES) $(foreach f,$(FIGURE_NAMES),$(DATA_$(f)))

# Maintainers: refresh the PNGs shown by README.md (docs/figures/).
figures-docs: figures-only
	cp $(foreach f,$(FIGURE_NAMES),$(FIG_DIR)/$(f).png) docs/figures/

# ---- rules ---------------------------------------------------------------------------
$(PARAMS_DIR) $(PLOT_TMP):
	@mkdir -p $@

# Parameter stamp: replaced only when the command line it records changes. Read, compared
# and written by make itself: the recipe expands to nothing, so the 63 stamps of a run start no
# process (a shell, cmp and rm each cost ~0.15 s of CPU per run). The text is first held in a
# simple variable: with the expansion inside findstring, make 4.3 found fig_md_lambda's text
# (nested foreach and call) different from its own stamp and rewrote it on every run.
# A dry run (make -n) leaves the stamps alone, as it leaves every file.
same_text = $(and $(findstring $(1),$(2)),$(findstring $(2),$(1)))
dry_run := $(findstring n,$(firstword -$(MAKEFLAGS)))
$(PARAMS_DIR)/%.params: $(FIGURES_CONF) FORCE | $(PARAMS_DIR)
	$(if $(dry_run),,$(eval stamp_text := $(CMD_$*)$(GP_$*))$(eval stamp_old := $(file <$@))$(if \
	  $(call same_text,$(stamp_old),$(stamp_text)),,$(file >$@,$(stamp_text))))

# Passive OpenMP waits: $(JOBS) processes share the cores, so a thread spinning for work
# takes them from another dataset (the numbers do not depend on it).
$(DATA_DIR)/%.tsv: $(PARAMS_DIR)/%.params $(CLI)
	$(info $(space) data  $@)@$(if $(SOLVE_CACHE),COATCONTACT_CACHE='$(SOLVE_CACHE)' )OMP_WAIT_POLICY=PASSIVE $(CLI) $(CMD_$*) --output $@

# Plots. One gnuplot process draws several figures, each in both formats: fmt selects the
# terminal in style.gp, and `reset session` before every pass starts it from gnuplot's defaults
# as a separate run would (the PNGs and PDFs are byte for byte those of one process per
# figure, the PDFs' creation date aside). A process costs ~25 ms of start-up, font set-up and
# caches per figure: the 16 figures took 1.43 s of CPU in 16 processes, 1.05 s in 2.
# Under figures-only (and figures-docs) an out-of-date figure's rule only queues the figure
# (PLOT_QUEUE, in make's memory: no process), and figures-only, once every dataset is made,
# plots the queue with PLOT_GROUPS processes at once (default $(JOBS)), each taking every
# PLOT_GROUPS-th queued figure. A figure asked for alone is plotted by its own rule.
PLOT_GROUPS ?= $(JOBS)
PLOT_BATCH  := $(filter figures-only figures-docs,$(MAKECMDGOALS))
PLOT_QUEUE  :=
plot_passes = -e "reset session" -e "fmt='png'; outfile='$(PLOT_TMP)/$(1).png'; $(GP_$(1))" $(GNUPLOT_DIR)/$(1).gp \
  -e "reset session" -e "fmt='pdf'; outfile='$(PLOT_TMP)/$(1).pdf'; $(GP_$(1))" $(GNUPLOT_DIR)/$(1).gp
# plot_figures(names): one gnuplot process for them all, then the renames; when it fails, no
# partial file stays and the figures stay out of date.
plot_figures = $(GNUPLOT) $(foreach f,$(1),$(call plot_passes,$(f))) \
  && mv -f $(foreach f,$(1),$(PLOT_TMP)/$(f).png $(PLOT_TMP)/$(f).pdf) $(FIG_DIR)/ \
  || { rm -f $(foreach f,$(1),$(PLOT_TMP)/$(f).png $(PLOT_TMP)/$(f).pdf); exit 1; }
plot_echo = $(foreach f,$(1),echo "  plot  $(FIG_DIR)/$(f).png"; echo "  plot  $(FIG_DIR)/$(f).pdf";)
# every_nth(list, n words): the 1st, (n+1)th, (2n+1)th, ... word of list.
every_nth = $(if $(1),$(firstword $(1)) $(call every_nth,$(wordlist $(words x $(2)),$(words $(1)),$(1)),$(2)))
# plot_groups(names): group k (k = 1..PLOT_GROUPS) takes names k, k + PLOT_GROUPS, ...; each
# group in the background, the exit status of all of them.
plot_groups = $(foreach k,$(wordlist 1,$(words $(wordlist 1,$(PLOT_GROUPS),$(1))),1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16), \
  ( $(call plot_figures,$(call every_nth,$(wordlist $(k),$(words $(1)),$(1)),$(wordlist 1,$(PLOT_GROUPS),$(1)))) ) & pids="$$pids $$!";)
define plot_queued
$(if $(PLOT_QUEUE),@$(call plot_echo,$(filter $(PLOT_QUEUE),$(FIGURE_NAMES))) pids=; \
  $(call plot_groups,$(filter $(PLOT_QUEUE),$(FIGURE_NAMES))) \
  rc=0; for p in $$pids; do wait $$p || rc=1; done; exit $$rc)
endef

$(FIG_DIR)/%.png $(FIG_DIR)/%.pdf: $(GNUPLOT_DIR)/%.gp $(GNUPLOT_DIR)/style.gp $(PARAMS_DIR)/%.params | $(PLOT_TMP)
	$(if $(PLOT_BATCH),$(eval PLOT_QUEUE += $*),@$(call plot_echo,$*) $(call plot_figures,$*))

$(CLI):
	@echo "figures: $(CLI) not found: build it first (make build, or pass CLI=...)"; exit 1

FORCE:

# Name every stamp explicitly so make treats none of them as an intermediate file (DATASET_NAMES
# above).
$(foreach n,$(DATASET_NAMES) $(FIGURE_NAMES),$(PARAMS_DIR)/$(n).params):

# ---- journal PDFs: make figures-paper -------------------------------------------------
# The same data and scripts as the screen figures, drawn with fmt='paper' (style.gp): one- or
# two-column width (8.5 cm, 17.8 cm), 8 pt text, no titles, panels lettered; the symbols and
# panel contents are in captions.txt beside them. A figure is redrawn only when its data, its
# scripts or its parameters change (the same prerequisites as the screen figure).
PAPER_DIR   ?= $(FIG_DIR)/paper
PAPER_FILES := $(foreach f,$(FIGURE_NAMES),$(PAPER_DIR)/$(f).pdf) $(PAPER_DIR)/captions.txt
$(foreach f,$(FIGURE_NAMES),$(eval $(PAPER_DIR)/$(f).pdf: $(DATA_$(f)) $(SCRIPTS_$(f))))

.PHONY: figures-paper figures-paper-only
figures-paper: build-cli
	@$(MAKE) --no-print-directory $(if $(filter -j%,$(MAKEFLAGS)),,-j$(JOBS)) figures-paper-only \
	  SOLVE_CACHE='$(if $(SOLVE_CACHE),$(SOLVE_CACHE),$(BUILD)/cache)'
figures-paper-only: $(PAPER_FILES)
	@echo "journal figures: $(PAPER_DIR)/*.pdf (8.5 or 17.8 cm wide), captions: $(PAPER_DIR)/captions.txt"

$(PAPER_DIR):
	@mkdir -p $@
$(PAPER_DIR)/%.pdf: $(GNUPLOT_DIR)/%.gp $(GNUPLOT_DIR)/style.gp $(PARAMS_DIR)/%.params | $(PAPER_DIR)
	@echo "  paper $@"
	@$(GNUPLOT) -e "fmt='paper'; outfile='$@.tmp'; $(GP_$*)" $< && mv -f $@.tmp $@ || { rm -f $@.tmp; exit 1; }
$(PAPER_DIR)/captions.txt: $(GNUPLOT_DIR)/captions.txt | $(PAPER_DIR)
	@cp $< $@.tmp && mv -f $@.tmp $@
