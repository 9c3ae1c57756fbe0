// wboit-msaa-exposure: the additive variant with the exposure curve
// 1 − exp(−k·c) instead of clamping (document 001's discussion). wboit_msaa.fxh holds it all.
#define WBOIT_MSAA_ADDITIVE 1
#define WBOIT_MSAA_EXPOSURE 1
#include "wboit_msaa.fxh"
