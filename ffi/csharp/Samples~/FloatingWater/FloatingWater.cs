// A springwater surface as a Unity Mesh, with Rigidbodies floating on it.
//
// Put it on an empty GameObject (it adds a MeshFilter and a MeshRenderer; give the renderer a
// material whose shader reads the normal and uv0), list the Rigidbodies to float in
// `bodies`. Each frame the water advances by Time.deltaTime, writes its packed vertex buffer
// (position, normal, refracted bottom uv: 32 bytes per node) and uploads it with one
// SetVertexBufferData; the LOD index buffer is uploaded only when the eye moved enough to
// change it. Each physics step every body feels the buoyancy and drag of the water under it,
// as a sphere of `bodyRadius`, and the water gets the opposite push. Nothing allocates per
// frame. The water lives in this GameObject's local space (one unit per node spacing, y up):
// move and rotate the GameObject, do not scale it.
using Springwater;
using UnityEngine;
using UnityEngine.Rendering;

[RequireComponent(typeof(MeshFilter), typeof(MeshRenderer))]
public sealed class FloatingWater : MonoBehaviour
{
    public int cols = 128;
    public int rows = 128;
    [Tooltip("Depth of the pool's bottom under the calm surface, for the refraction uv")]
    public float depth = 4f;
    public Rigidbody[] bodies = new Rigidbody[0];
    [Tooltip("Each body floats as a sphere of this radius")]
    public float bodyRadius = 0.5f;
    [Tooltip("Mass of water per cubic unit, in the Rigidbodies' mass units")]
    public float density = 1f;
    [Tooltip("Drag per second, times the displaced water's mass and the speed relative to the water")]
    public float drag = 3f;

    WaterSurface water;
    Mesh mesh;
    SwVertex[] vertices;
    uint[] indices = new uint[0];
    SwRefraction view;
    float forceToLattice;
    // Per body: where it is (x, z pairs in the water's space), the water there, found or not.
    float[] points;
    SwSample[] samples;
    byte[] found;

    void Start()
    {
        water = new WaterSurface(cols, rows);
        SwParams p = water.Params;
        // The water takes forces in its lattice units: per-second² forces divided by the
        // square of its model time per second.
        forceToLattice = 1f / (p.time_scale * p.time_scale);
        vertices = new SwVertex[water.NodeCount];
        view = SwRefraction.Default();
        view.depth = depth;

        mesh = new Mesh();
        mesh.name = "springwater";
        mesh.indexFormat = IndexFormat.UInt32;
        mesh.SetVertexBufferParams(vertices.Length,
            new VertexAttributeDescriptor(VertexAttribute.Position, VertexAttributeFormat.Float32, 3),
            new VertexAttributeDescriptor(VertexAttribute.Normal, VertexAttributeFormat.Float32, 3),
            new VertexAttributeDescriptor(VertexAttribute.TexCoord0, VertexAttributeFormat.Float32, 2));
        float width = (cols - 1) * p.spacing, length = (rows - 1) * p.spacing;
        mesh.bounds = new Bounds(new Vector3(width / 2, 0, length / 2), new Vector3(width, 2 * depth, length));
        GetComponent<MeshFilter>().sharedMesh = mesh;

        points = new float[2 * bodies.Length];
        samples = new SwSample[bodies.Length];
        found = new byte[bodies.Length];
        water.DropAt(width / 2, length / 2, 1f, 3f * p.spacing);
    }

    void Update()
    {
        water.Advance(Time.deltaTime);
        Camera eye = Camera.main;
        Vector3 e = eye != null ? transform.InverseTransformPoint(eye.transform.position) : Vector3.up;
        view.eye_x = e.x;
        view.eye_y = e.y;
        view.eye_z = e.z;

        water.WriteVertices(view, vertices);
        const MeshUpdateFlags quiet = MeshUpdateFlags.DontRecalculateBounds | MeshUpdateFlags.DontValidateIndices;
        mesh.SetVertexBufferData(vertices, 0, 0, vertices.Length, 0, quiet);

        if (water.UpdateLod(e.x, e.y, e.z))
        {
            int count = water.LodIndexCount;
            if (indices.Length < count)
                indices = new uint[count];
            water.WriteLodIndices(indices);
            mesh.SetIndexBufferParams(count, IndexFormat.UInt32);
            mesh.SetIndexBufferData(indices, 0, 0, count, quiet);
            mesh.subMeshCount = 1;
            mesh.SetSubMesh(0, new SubMeshDescriptor(0, count, MeshTopology.Triangles), quiet);
        }
    }

    void FixedUpdate()
    {
        for (int k = 0; k < bodies.Length; k++)
        {
            Vector3 local = transform.InverseTransformPoint(bodies[k].position);
            points[2 * k] = local.x;
            points[2 * k + 1] = local.z;
        }
        // One call for every body; a body off the water is simply not found.
        water.SampleEach(points, samples, found);
        float g = -Physics.gravity.y, r = bodyRadius;
        for (int k = 0; k < bodies.Length; k++)
        {
            if (found[k] == 0)
                continue;
            Rigidbody body = bodies[k];
            Vector3 local = transform.InverseTransformPoint(body.position);
            // The part of the sphere under the water: a cap of depth d, volume π d² (3r − d) / 3.
            float d = Mathf.Clamp(samples[k].height - (local.y - r), 0f, 2f * r);
            if (d <= 0f)
                continue;
            float displaced = density * Mathf.PI * d * d * (3f * r - d) / 3f;
            Float3 flow = samples[k].Velocity;
#if UNITY_6000_0_OR_NEWER
            Vector3 velocity = transform.InverseTransformDirection(body.linearVelocity);
#else
            Vector3 velocity = transform.InverseTransformDirection(body.velocity);
#endif
            Vector3 relative = velocity - new Vector3(flow.x, flow.y, flow.z);
            Vector3 force = displaced * g * Vector3.up - drag * displaced * relative;
            body.AddForce(transform.TransformDirection(force), ForceMode.Force);
            // What the body gets, the water loses.
            water.AddForceAt(points[2 * k], points[2 * k + 1],
                -force.x * forceToLattice, -force.y * forceToLattice, -force.z * forceToLattice);
        }
    }

    void OnDestroy()
    {
        if (water != null)
            water.Dispose();
        if (mesh != null)
            Destroy(mesh);
    }
}
