/* k_cloth.h - cloth models (Neubelt-Pettineo Eq. 10, Kajiya-Kay Eq. 11). */

#define ABRDF__CLOTH_MODELS(X)

static inline void FN(kp_make_cloth)(kp *k, abrdf_model model, const abrdf_params *p)
{
    (void)k; (void)model; (void)p;
}
