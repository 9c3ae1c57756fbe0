// A transparency method's own passes, those that draw no object (composing):
// the method's include (renderer/oit loads this file with OIT_METHOD defined to
// "oit/<method>.fxh") without an object, so OBJECT_VS stays undefined. A method
// whose passes all draw objects (alpha) yields an effect with no technique.
#include OIT_METHOD
