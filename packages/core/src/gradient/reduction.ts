/** Side of the block each reduction texel takes the maximum of. */
export const REDUCTION = 8;
