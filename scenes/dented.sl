/*
 * dented — a displacement shader: the surface moved along its normal by Km times a noise of
 * its position in shader space, so the dents stay on the object as it moves. The renderers
 * bump-map: the surface shader sees the normal of the moved surface.
 */
displacement dented(float Km = 0.04; float frequency = 5;)
{
    point Pshad = transform("shader", P);
    float n = noise(Pshad * frequency) + 0.5 * noise(Pshad * (2 * frequency));
    P += Km * (n - 0.75) * normalize(N);
}
