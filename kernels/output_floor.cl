/* The output floor of `clmarch bench`: the device storing as many floats as a march program's
 * planes and doing nothing else, a whole 64-byte row of value per work-item. No march kernel can
 * write its frame faster; the part of a frame's time beyond this is the march's. */
__kernel void fill_planes(__global float16* planes, const float value) { planes[get_global_id(0)] = (float16)(value); }
