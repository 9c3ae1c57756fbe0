// Colored OIT composed with Table 4 as printed (SPEC.md): INV_SRC_ALPHA / ONE
// adds C * revealage, the weighted colour scaled by the transmitted fraction
// (docs/blend_tables.md measures it); colored.fxh holds the rest of the method.
BlendState ColoredComposeLiteral {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = INV_SRC_ALPHA;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ZERO;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

#define COLORED_TECHNIQUE ColoredLiteral
#define COLORED_COMPOSE ColoredComposeLiteral
#include "colored.fxh"
