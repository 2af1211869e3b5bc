/* measured_standin.c - measured materials exported as fitted stand-ins (measured_standin.h). */
#include "measured_standin.h"

#include <stdlib.h>
#include <string.h>

#include "abrdf_fit.h"
#include "budget_run.h"
#include "cli_args.h"
#include "metrics.h"

/* The candidates: the models both hosts render natively or through their ports at the cost
 * of a closed form, the diffuse terms and the two microfacet lobes the fits of
 * docs/MEASURED.md ("A table of fits") rank first. Four fits per table: a fraction of a
 * second (`abrdf fit --to FILE --all` ranks every model). */
static const abrdf_model diffuse_candidates[] = {ABRDF_LAMBERT, ABRDF_DISNEY_DIFFUSE};
static const abrdf_model specular_candidates[] = {ABRDF_DISNEY_SPECULAR, ABRDF_COOK_TORRANCE};
#define N_DIFFUSE (int)(sizeof diffuse_candidates / sizeof diffuse_candidates[0])
#define N_SPECULAR (int)(sizeof specular_candidates / sizeof specular_candidates[0])

typedef struct standin {
    abrdf_model diffuse, specular;
    abrdf_params params;
    abrdf_fit_result res;
} standin;

/* The parameters `model` reads, copied from `from` into `to`. */
static void copy_read(abrdf_model model, const abrdf_params *from, abrdf_params *to)
{
    const abrdf_model_info *mi = abrdf_model_get(model);
    for (int i = 0; i < mi->param_count; ++i) {
        double v[3];
        int n = abrdf_param_read(from, mi->params[i].id, v);
        if (n > 0) abrdf_param_set(to, mi->params[i].id, v, n);
    }
}

/* Does `a` read a parameter `b` reads? (One block holds both lobes' parameters.) */
static int share_params(abrdf_model a, abrdf_model b)
{
    const abrdf_model_info *mi = abrdf_model_get(a);
    for (int i = 0; i < mi->param_count; ++i)
        if (cli_model_reads(b, mi->params[i].id)) return 1;
    return 0;
}

/* Best stand-in of material m's table (the material keeps its own diffuse lobe if it has
 * one, and a specular lobe that would share a parameter with it - disney_diffuse's r - is no
 * candidate: the block holds one value). 0, or -1 with the message. */
static int fit_standin(const scene *s, const scene_material *m, standin *best, void *work,
                       size_t work_size, char *err, size_t err_size)
{
    const measured_table *t = &s->measured[m->measured].table;
    abrdf_measured desc;
    abrdf_measured_init(&desc);
    desc.n_theta_h = t->n_theta_h, desc.n_theta_d = t->n_theta_d, desc.n_phi_d = t->n_phi_d;
    desc.data = t->data;
    abrdf_prepared ref;
    if (abrdf_prepare_measured(&desc, &ref) != ABRDF_OK) {
        snprintf(err, err_size, "material '%s': its table cannot be prepared", m->name);
        return -1;
    }
    int own_diffuse = m->lobe_count == 2; /* lobes = {diffuse, measured} */
    abrdf_fit_options opt;
    abrdf_fit_options_init(&opt);
    best->res.nmse_pred = -1.0;
    for (int d = 0; d < (own_diffuse ? 1 : N_DIFFUSE); ++d)
        for (int k = 0; k < N_SPECULAR; ++k) {
            standin c;
            c.diffuse = own_diffuse ? ABRDF_MODEL_NONE : diffuse_candidates[d];
            c.specular = specular_candidates[k];
            if (own_diffuse && share_params(m->lobes[0], c.specular)) continue;
            abrdf_params_init(c.specular, &c.params);
            abrdf_fit_result_init(&c.res);
            int st =
                abrdf_fit_to(&ref, c.diffuse, c.specular, &c.params, &opt, &c.res, work, work_size);
            if (st != ABRDF_OK) {
                snprintf(err, err_size, "material '%s': fitting %s to its table: %s", m->name,
                         abrdf_model_get(c.specular)->name, c.res.message);
                return -1;
            }
            if (best->res.nmse_pred < 0 || c.res.nmse_pred < best->res.nmse_pred) *best = c;
        }
    if (best->res.nmse_pred < 0) {
        snprintf(err, err_size,
                 "material '%s': every stand-in lobe reads a parameter of its diffuse lobe %s, "
                 "which the exported material could hold only once (use kd= or diffuse=lambert)",
                 m->name, abrdf_model_get(m->lobes[0])->name);
        return -1;
    }
    return 0;
}

int measured_standins(scene *s, FILE *notes, char *err, size_t err_size)
{
    abrdf_fit_options opt;
    abrdf_fit_options_init(&opt);
    size_t work_size = abrdf_fit_workspace_size(&opt, NULL);
    void *work = NULL;
    for (int i = 0; i < s->material_count; ++i) {
        scene_material *m = &s->materials[i];
        if (m->measured < 0) continue;
        if (!work && !(work = malloc(work_size))) {
            snprintf(err, err_size, "out of memory");
            return -1;
        }
        standin best;
        if (fit_standin(s, m, &best, work, work_size, err, err_size)) {
            free(work);
            return -1;
        }
        const char *path = s->measured[m->measured].path;
        abrdf_model own = m->lobes[0];
        int own_diffuse = m->lobe_count == 2;
        if (own_diffuse) { /* the material's diffuse lobe and its parameters stay */
            copy_read(best.specular, &best.params, &m->params);
            m->lobes[1] = best.specular;
        } else {
            m->params = best.params;
            m->lobes[0] = best.diffuse;
            m->lobes[1] = best.specular;
            m->lobe_count = 2;
        }
        m->measured = -1;
        fprintf(notes,
                "material %s: the host cannot read the measured table %s (docs/MEASURED.md, "
                "\"In other renderers\"); its fitted stand-in %s%s + %s, fit rel. L2 %.3g, "
                "predicted image NMSE %.3g (%s; the default sphere): ",
                m->name, path, abrdf_model_get(own_diffuse ? own : best.diffuse)->name,
                own_diffuse ? " (the material's)" : "", abrdf_model_get(best.specular)->name,
                best.res.rel_l2, best.res.nmse_pred, abrdf_nmse_class(best.res.nmse_pred));
        budget_params_text(notes, own_diffuse ? ABRDF_MODEL_NONE : best.diffuse, best.specular,
                           &best.params);
        fputc('\n', notes);
    }
    free(work);
    return 0;
}
