// wboit-msaa-linear: the additive variant blended in linear colour with an sRGB
// frame (document 001's discussion). wboit_msaa.fxh holds it all.
#define WBOIT_MSAA_ADDITIVE 1
#define WBOIT_MSAA_LINEAR 1
#include "wboit_msaa.fxh"
