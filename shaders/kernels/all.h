// Every shared kernel body, in dependency order.
#include "kernels/common.h"
#include "kernels/contact_law.h"
#include "kernels/walls.h"
#include "kernels/integrate.h"
#include "kernels/bodies.h"
#include "kernels/neighbour.h"
#include "kernels/contacts.h"
