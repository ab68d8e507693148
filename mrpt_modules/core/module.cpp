#include "mrpt_modules/core/module.h"

IMPLEMENTS_VIRTUAL_MRPT_OBJECT(Module, mrpt::rtti::CObject, rpvio)
