// wboit-msaa-additive: document 001's discussion, plain additive blending
// (premultiplied, ONE/ONE, no division): C0 + Σ w·c. wboit_msaa.fxh holds it all.
#define WBOIT_MSAA_ADDITIVE 1
#include "wboit_msaa.fxh"
