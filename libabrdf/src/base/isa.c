/* isa.c - the instruction-set level this CPU runs (isa.h). */
#include "isa.h"

int abrdf__isa_best(void) { return abrdf__isa_best_inline(); }
